// payload: an unmodelled point mass at the tool, ONE mass (kg) and centre of mass (m, tool frame)
// for the whole arm. Its regressor is arcplan's payload regressor (robot/dynamics.h): the torque
// on each joint is linear in [m, m·cx, m·cy, m·cz]; the fit sees it through each joint's drive gain.
#include <cmath>

#include "arcplan/model/dataset.h"
#include "arcplan/model/effect.h"
#include "model_internal.h"

namespace arcplan::model::detail {
namespace {

class Payload : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override {
    return "an unmodelled mass at the tool (gravity and inertia of a point mass)";
  }
  std::string term() const override {
    return "k_j·Y_payload,j(q,qd,qdd)·[m, m·cx, m·cy, m·cz], one m and c for the arm";
  }
  std::string residualPattern() const override {
    return "follows the gravity and acceleration torque of a mass carried at the tool";
  }
  bool appliesTo(ModelKind kind) const override { return kind == ModelKind::JointCurrent; }
  std::vector<std::string> requiredSignals() const override {
    return {"payload_m", "payload_mx", "payload_my", "payload_mz"};
  }
  std::vector<std::string> parameterNames() const override { return {"m", "m_cx", "m_cy", "m_cz"}; }
  // The payload a simulation puts on the arm when the model file gives no fitted parameters.
  std::vector<std::string> optionNames() const override {
    return {"mass_kg", "center_of_mass_x", "center_of_mass_y", "center_of_mass_z"};
  }
  void regressor(const Dataset& data, int c, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    columns.col(0) = data.signal("payload_m", c);
    columns.col(1) = data.signal("payload_mx", c);
    columns.col(2) = data.signal("payload_my", c);
    columns.col(3) = data.signal("payload_mz", c);
  }
  bool sharedAcrossChannels() const override { return true; }

  std::vector<PhysicalQuantity> physicalQuantities(const Eigen::VectorXd& theta,
                                                   const Eigen::MatrixXd& covariance) const override {
    if (theta.size() != 4) return {};  // parameters read from a file: per channel, no joint estimate
    const double mass = theta[0];
    PhysicalQuantity massQuantity{"mass_kg", "payload mass", {mass}, {std::sqrt(covariance(0, 0))}};
    // c = (m·c) / m; standard errors by first-order propagation (the delta method).
    PhysicalQuantity center{"center_of_mass_m", "payload centre of mass in the tool (tip link) frame", {}, {}};
    for (int i = 1; i <= 3; ++i) {
      Eigen::Vector4d gradient = Eigen::Vector4d::Zero();
      gradient[0] = -theta[i] / (mass * mass);
      gradient[i] = 1.0 / mass;
      center.values.push_back(theta[i] / mass);
      center.standardErrors.push_back(std::sqrt(gradient.dot(covariance * gradient)));
    }
    return {massQuantity, center};
  }

  std::vector<double> typicalParameters(ModelKind, int c) const override {
    // 3 kg, 5 cm out along the tool axis unless the model file says otherwise.
    const double mass = option("mass_kg").value_or(3.0);
    const double gain = typicalDriveGain(c);
    return {gain * mass, gain * mass * option("center_of_mass_x").value_or(0.0),
            gain * mass * option("center_of_mass_y").value_or(0.0),
            gain * mass * option("center_of_mass_z").value_or(0.05)};
  }
};

}  // namespace

EffectFactory payloadFactory() {
  return [](const EffectSpec& spec) { return std::make_unique<Payload>(spec); };
}

}  // namespace arcplan::model::detail
