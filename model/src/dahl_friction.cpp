// dahl_friction: friction with memory (Dahl's model). The friction state z follows the joint's
// displacement, dz/dq = ρ·(1 - z·sgn(dq)): it rises over a few 1/ρ rad after every reversal and
// saturates at ±1 (Coulomb) while sliding; when the joint stops, z keeps the value it had, so a
// joint at rest holds a current that depends on how it stopped (pre-sliding hysteresis). The term
// is Fd·z(ρ): Fd is linear, ρ is searched (variable projection: Fd solved exactly for each ρ,
// ρ by grid and golden section, i.e. nonlinear least squares in one dimension).
#include <cmath>

#include "arcplan/model/dataset.h"
#include "arcplan/model/effect.h"
#include "model_internal.h"

namespace arcplan::model::detail {
namespace {

class DahlFriction : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override {
    return "friction with memory (Dahl model, pre-sliding hysteresis): after each reversal the friction builds "
           "up over a small displacement, and a joint that stops keeps the friction it had";
  }
  std::string term() const override { return "Fd·z, dz/dq = rate·(1 - z·sgn(dq)), z simulated along the log"; }
  std::string residualPattern() const override {
    return "depends on the recent direction of motion: it builds up over a small angle after each reversal and "
           "stays while the joint stands still";
  }
  bool appliesTo(ModelKind kind) const override { return kind == ModelKind::JointCurrent; }
  std::vector<std::string> requiredSignals() const override { return {"q"}; }
  std::vector<std::string> parameterNames() const override { return {"Fd"}; }
  std::optional<NonlinearParameter> nonlinearParameter() const override {
    NonlinearParameter p{"dahl_rate", "1/rad", {}, false};
    for (int i = 0; i <= 40; ++i) p.grid.push_back(3.0 * std::pow(1e4, i / 40.0));  // 3 .. 30000 /rad
    return p;
  }
  // Exact integration over each sample step (the direction is constant within it):
  // z ← s + (z - s)·exp(-ρ·|Δq|), s = sgn(Δq); z starts at 0 at the start of every run (the state
  // before a run is unknown; the step from one run's end to the next's start is no motion).
  void regressor(const Dataset& data, int c, double rate, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    const auto& q = data.signal("q", c);
    const std::vector<bool> begins = runBeginnings(data, q.size());
    double z = 0.0;
    for (Eigen::Index k = 0; k < q.size(); ++k) {
      if (begins[static_cast<std::size_t>(k)]) {
        columns(k, 0) = z = 0.0;
        continue;
      }
      const double step = q[k] - q[k - 1];
      if (step != 0.0) {
        const double direction = step > 0.0 ? 1.0 : -1.0;
        z = direction + (z - direction) * std::exp(-rate * std::abs(step));
      }
      columns(k, 0) = z;
    }
  }
  std::vector<double> typicalParameters(ModelKind, int c) const override { return {0.5 * typicalCoulomb(c)}; }
  double typicalNonlinear(int) const override { return 30.0; }
};

}  // namespace

EffectFactory dahlFrictionFactory() {
  return [](const EffectSpec& spec) { return std::make_unique<DahlFriction>(spec); };
}

}  // namespace arcplan::model::detail
