// maxwell_slip: friction with memory as several elasto-slip elements side by side (the Maxwell-slip
// model). Element i is a spring that sticks until its deflection reaches its breakaway
// displacement Δ_i and slips beyond it; along the log, at every sample step,
//   δ_i ← clamp(δ_i + Δq, −Δ_i, Δ_i),
// and it holds the force k_i·δ_i. The Δ_i are fixed (a geometric grid Δ_1·3^(i−1)), so the friction
// Σ k_i·δ_i = Σ F_i·z_i with z_i = δ_i/Δ_i in [−1, 1] is linear in the element levels F_i = k_i·Δ_i
// (least squares, no search). Unlike Dahl's state, an element moved back and forth by less than its
// breakaway returns to the deflection it had (closed minor loops): the encoder steps of a joint at
// rest do not wipe the memory of how it stopped. With `load_scaled: 1` every level grows with the
// load torque, (F_i + G_i·|tau|)·z_i (friction pressed by the load, as load_friction).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "arcplan/common/error.h"
#include "arcplan/model/dataset.h"
#include "arcplan/model/effect.h"
#include "model_internal.h"

namespace arcplan::model::detail {
namespace {

constexpr int kMaxElements = 20;
constexpr double kGridRatio = 3.0;  // between neighbouring breakaway displacements

class MaxwellSlipFriction : public Effect {
public:
  explicit MaxwellSlipFriction(const EffectSpec& spec) : Effect(spec) {
    const double count = option("elements").value_or(5.0);
    if (!(count >= 1 && count <= kMaxElements && count == std::floor(count))) {
      throw Error("effect '" + spec.id + "': option elements: expected a whole number from 1 to " +
                  std::to_string(kMaxElements) + ", got " + number(count));
    }
    elements_ = static_cast<int>(count);
    smallest_ = option("breakaway_rad").value_or(1e-4);
    if (!(smallest_ > 0.0 && std::isfinite(smallest_))) {
      throw Error("effect '" + spec.id + "': option breakaway_rad: expected a positive angle in rad, got " +
                  number(smallest_));
    }
    const double scaled = option("load_scaled").value_or(0.0);
    if (scaled != 0.0 && scaled != 1.0) {
      throw Error("effect '" + spec.id + "': option load_scaled: expected 0 or 1, got " + number(scaled));
    }
    loadScaled_ = scaled == 1.0;
  }
  std::string meaning() const override {
    return std::string("friction with memory (Maxwell-slip: elasto-slip elements with breakaway displacements from ") +
           number(smallest_) + " rad): each element sticks until it is deflected by its breakaway and slips beyond, " +
           "so a joint that stops keeps the friction it had, also through small steps back and forth" +
           (loadScaled_ ? "; every element's level grows with the load torque" : "");
  }
  std::string term() const override {
    return std::string(loadScaled_ ? "Σ (F_i + G_i·|tau|)·z_i" : "Σ F_i·z_i") +
           ", z_i = δ_i/Δ_i, δ_i ← clamp(δ_i + Δq, ±Δ_i), Δ_i = breakaway_rad·3^(i-1)";
  }
  std::string residualPattern() const override {
    return "depends on the recent path of the joint: it builds up over small angles after each reversal and stays, "
           "also through small back-and-forth steps, while the joint stands still";
  }
  bool appliesTo(ModelKind kind) const override { return kind == ModelKind::JointCurrent; }
  std::vector<std::string> requiredSignals() const override {
    return loadScaled_ ? std::vector<std::string>{"q", "tau"} : std::vector<std::string>{"q"};
  }
  std::vector<std::string> optionNames() const override { return {"elements", "breakaway_rad", "load_scaled"}; }
  std::vector<std::string> parameterNames() const override {
    std::vector<std::string> names;
    for (int i = 1; i <= elements_; ++i) names.push_back("F" + std::to_string(i));
    for (int i = 1; loadScaled_ && i <= elements_; ++i) names.push_back("G" + std::to_string(i));
    return names;
  }
  // The elements start undeflected at the start of every run (the state before a run is unknown;
  // the step from one run's end to the next's start is no motion).
  void regressor(const Dataset& data, int c, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    const auto& q = data.signal("q", c);
    const std::vector<bool> begins = runBeginnings(data, q.size());
    std::vector<double> breakaway(static_cast<std::size_t>(elements_)), deflection(breakaway.size(), 0.0);
    for (int i = 0; i < elements_; ++i) breakaway[i] = smallest_ * std::pow(kGridRatio, i);
    const Eigen::VectorXd* tau = loadScaled_ ? &data.signal("tau", c) : nullptr;
    for (Eigen::Index k = 0; k < q.size(); ++k) {
      const bool runBegins = begins[static_cast<std::size_t>(k)];
      if (runBegins) std::fill(deflection.begin(), deflection.end(), 0.0);
      const double step = runBegins ? 0.0 : q[k] - q[k - 1];
      for (int i = 0; i < elements_; ++i) {
        deflection[i] = std::clamp(deflection[i] + step, -breakaway[i], breakaway[i]);
        const double z = deflection[i] / breakaway[i];
        columns(k, i) = z;
        if (tau) columns(k, elements_ + i) = z * std::abs((*tau)[k]);
      }
    }
  }
  std::vector<double> typicalParameters(ModelKind, int c) const override {
    // Half the Coulomb level spread evenly over the elements; loaded, 1 % more per N·m.
    std::vector<double> values(static_cast<std::size_t>(elements_), 0.5 * typicalCoulomb(c) / elements_);
    if (loadScaled_) values.resize(2 * values.size(), 0.005 * typicalCoulomb(c) / elements_);
    return values;
  }

private:
  static std::string number(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", value);
    return buffer;
  }
  int elements_ = 5;
  double smallest_ = 1e-4;  // rad, the first element's breakaway displacement
  bool loadScaled_ = false;
};

}  // namespace

EffectFactory maxwellSlipFrictionFactory() {
  return [](const EffectSpec& spec) { return std::make_unique<MaxwellSlipFriction>(spec); };
}

}  // namespace arcplan::model::detail
