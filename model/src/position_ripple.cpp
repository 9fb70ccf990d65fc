// position_ripple: a term periodic in the joint angle (gear meshing, the Harmonic Drive's wave
// generator), its spatial frequency searched over 1–500 cycles per revolution at once.
#include <algorithm>
#include <cmath>
#include <complex>

#include "arcplan/model/dataset.h"
#include "arcplan/model/effect.h"
#include "model_internal.h"

namespace arcplan::model::detail {
namespace {

class PositionRipple : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override {
    return "periodic in the joint angle: gear meshing and the wave generator of the Harmonic Drive";
  }
  std::string term() const override {
    return "sum_k a_k·cos(k·n·q) + b_k·sin(k·n·q), n cycles per revolution searched";
  }
  std::string residualPattern() const override { return "repeats periodically with the joint angle"; }
  bool appliesTo(ModelKind kind) const override {
    return kind == ModelKind::JointCurrent || kind == ModelKind::JointTracking;
  }
  std::vector<std::string> requiredSignals() const override { return {"q"}; }
  std::vector<std::string> optionNames() const override { return {"harmonics"}; }
  int harmonics() const { return std::max(1, static_cast<int>(option("harmonics").value_or(1.0))); }
  std::vector<std::string> parameterNames() const override {
    std::vector<std::string> names;
    for (int k = 1; k <= harmonics(); ++k) {
      names.push_back("a" + std::to_string(k));
      names.push_back("b" + std::to_string(k));
    }
    return names;
  }
  std::optional<NonlinearParameter> nonlinearParameter() const override {
    NonlinearParameter p{"cycles_per_revolution", "1/rev", {}, true};
    for (int n = kMinCycles; n <= kMaxCycles; ++n) p.grid.push_back(n);
    return p;
  }
  void regressor(const Dataset& data, int c, double cycles, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    const auto& q = data.signal("q", c);
    for (int k = 1; k <= harmonics(); ++k) {
      for (Eigen::Index i = 0; i < q.size(); ++i) {
        const double phase = k * cycles * q[i];
        columns(i, 2 * (k - 1)) = std::cos(phase);
        columns(i, 2 * (k - 1) + 1) = std::sin(phase);
      }
    }
  }

  // All 500 frequencies at once: the sums Σ r·e^{inq} and Σ e^{imq} come from one complex
  // recurrence per point, and the points are the residual binned finely in q (bins a 32nd of the
  // shortest period, so the phase error stays below 0.1 rad) when that is fewer than the samples.
  // The other columns (`basis`) are not projected out: a ripple of many cycles per revolution is
  // nearly orthogonal to the smooth terms of a model, and the binning needs the plain residual.
  double searchNonlinear(const Dataset& data, int c, const Eigen::VectorXd& residual,
                         const Eigen::MatrixXd&) const override {
    if (const auto fixed = option("cycles_per_revolution")) return *fixed;
    const auto& q = data.signal("q", c);
    const double low = q.minCoeff(), high = q.maxCoeff();
    const double width = 2.0 * M_PI / kMaxCycles / 32.0;
    const auto binCount = static_cast<Eigen::Index>(std::floor((high - low) / width)) + 1;
    std::vector<double> position, weight, sum;
    if (binCount < q.size()) {
      std::vector<double> qSum(binCount, 0.0), count(binCount, 0.0), rSum(binCount, 0.0);
      for (Eigen::Index i = 0; i < q.size(); ++i) {
        const auto b = std::min<Eigen::Index>(binCount - 1, static_cast<Eigen::Index>((q[i] - low) / width));
        qSum[b] += q[i];
        count[b] += 1.0;
        rSum[b] += residual[i];
      }
      for (Eigen::Index b = 0; b < binCount; ++b) {
        if (count[b] == 0.0) continue;
        position.push_back(qSum[b] / count[b]);
        weight.push_back(count[b]);
        sum.push_back(rSum[b]);
      }
    } else {
      position.assign(q.data(), q.data() + q.size());
      weight.assign(q.size(), 1.0);
      sum.assign(residual.data(), residual.data() + residual.size());
    }
    // moments[m] = Σ w·e^{imq} (m ≤ 2·max), projections[n] = Σ r·e^{inq} (n ≤ max)
    std::vector<std::complex<double>> moments(2 * kMaxCycles + 1, 0.0), projections(kMaxCycles + 1, 0.0);
    for (std::size_t i = 0; i < position.size(); ++i) {
      const std::complex<double> step = std::polar(1.0, position[i]);
      std::complex<double> power = 1.0;
      for (int m = 1; m <= 2 * kMaxCycles; ++m) {
        power *= step;
        if (m % 64 == 0) power = std::polar(1.0, m * position[i]);  // stop rounding drift
        moments[m] += weight[i] * power;
        if (m <= kMaxCycles) projections[m] += sum[i] * power;
      }
    }
    double total = 0.0;
    for (double w : weight) total += w;
    int best = kMinCycles;
    double bestReduction = -1.0;
    for (int n = kMinCycles; n <= kMaxCycles; ++n) {
      // Gram of [cos nq, sin nq] from the double-angle moments.
      const double cc = 0.5 * (total + moments[2 * n].real()), ss = 0.5 * (total - moments[2 * n].real());
      const double cs = 0.5 * moments[2 * n].imag();
      const double rc = projections[n].real(), rs = projections[n].imag();
      const double det = cc * ss - cs * cs;
      if (det <= 1e-9 * total * total) continue;
      const double reduction = (ss * rc * rc - 2.0 * cs * rc * rs + cc * rs * rs) / det;
      if (reduction > bestReduction) {
        bestReduction = reduction;
        best = n;
      }
    }
    return best;
  }
  std::vector<double> typicalParameters(ModelKind kind, int c) const override {
    std::vector<double> values(2 * harmonics(), 0.0);
    values[0] = kind == ModelKind::JointTracking ? 2e-4 : 0.2 * typicalCoulomb(c);
    values[1] = kind == ModelKind::JointTracking ? 1e-4 : 0.1 * typicalCoulomb(c);
    return values;
  }
  double typicalNonlinear(int) const override { return 50.0; }

private:
  static constexpr int kMinCycles = 1;
  static constexpr int kMaxCycles = 500;
};

}  // namespace

EffectFactory positionRippleFactory() {
  return [](const EffectSpec& spec) { return std::make_unique<PositionRipple>(spec); };
}

}  // namespace arcplan::model::detail
