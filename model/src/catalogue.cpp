// The effect catalogue (docs/model.md, "Effect catalogue"): the simple terms, one class each, and
// the one ordered table of every built-in effect. The typical values are what a UR10e shows
// (currents fitted on the real logs in shared/data/ur10e_real) and only serve `arcplan model
// simulate` when a model file gives no parameters.
#include <algorithm>
#include <cmath>
#include <map>

#include "arcplan/model/dataset.h"
#include "arcplan/model/effect.h"
#include "model_internal.h"

namespace arcplan::model::detail {
namespace {

// Per-joint typical values for a UR10e (joints beyond the sixth reuse the last one).
double typical(const std::vector<double>& values, int channel) {
  return values[static_cast<std::size_t>(std::min<int>(channel, static_cast<int>(values.size()) - 1))];
}
const std::vector<double> kDriveGain{0.085, 0.085, 0.10, 0.095, 0.09, 0.08};  // A/(N·m)
const std::vector<double> kCoulomb{1.4, 1.3, 0.65, 0.26, 0.3, 0.24};          // A
const std::vector<double> kViscous{1.75, 1.63, 1.09, 0.33, 0.24, 0.29};       // A·s/rad
const std::vector<double> kTorqueScale{10.0, 70.0, 30.0, 2.5, 0.5, 0.3};      // typical |τ| in N·m
const std::vector<double> kRotorInertia{6.0, 6.0, 1.9, 0.6, 0.6, 0.6};        // kg·m² at the joint

double sgn(const Dataset& data, double velocity) { return smoothedDirection(data, velocity); }

class RigidBody : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override {
    return "inertia, Coriolis and gravity torques of the arm computed from the URDF inertials";
  }
  std::string term() const override { return "a·g(q) + b·(M(q)·qdd + C(q,qd)·qd)"; }
  std::string residualPattern() const override {
    return "follows the arm's own rigid-body torque (gravity and inertia of the URDF links)";
  }
  bool appliesTo(ModelKind kind) const override { return kind == ModelKind::JointCurrent; }
  std::vector<std::string> requiredSignals() const override { return {"rb_gravity", "rb_inertial"}; }
  std::vector<std::string> parameterNames() const override { return {"gravity_gain", "inertial_gain"}; }
  void regressor(const Dataset& data, int c, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    columns.col(0) = data.signal("rb_gravity", c);
    columns.col(1) = data.signal("rb_inertial", c);
  }
  std::vector<double> typicalParameters(ModelKind, int c) const override {
    // The arm's inertia 30 % above what the load-torque source assumes.
    return {0.0, 0.3 * typical(kDriveGain, c)};
  }
};

class DriveGain : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override {
    return "torque per amp of the drive (gear ratio x motor torque constant); for a gearbox, the slope of the "
           "force-transfer line";
  }
  std::string term() const override { return "current = tau / k  (coefficient 1/k)"; }
  std::string residualPattern() const override { return "is proportional to the load torque"; }
  bool appliesTo(ModelKind kind) const override { return kind != ModelKind::JointTracking; }
  std::vector<std::string> requiredSignals() const override { return {"tau"}; }
  std::vector<std::string> parameterNames() const override { return {"per_torque"}; }
  void regressor(const Dataset& data, int c, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    columns.col(0) = data.signal("tau", c);
  }
  std::vector<double> typicalParameters(ModelKind, int c) const override { return {typical(kDriveGain, c)}; }
};

class Offset : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override { return "constant sensor or current offset"; }
  std::string term() const override { return "c"; }
  std::string residualPattern() const override { return "has a constant offset"; }
  bool appliesTo(ModelKind) const override { return true; }
  std::vector<std::string> requiredSignals() const override { return {}; }
  std::vector<std::string> parameterNames() const override { return {"offset"}; }
  void regressor(const Dataset&, int, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    columns.col(0).setOnes();
  }
  std::vector<double> typicalParameters(ModelKind kind, int c) const override {
    const std::vector<double> amps{0.02, -0.05, 0.01, 0.01, 0.015, 0.005};
    return {kind == ModelKind::JointTracking ? 1e-4 : typical(amps, c)};
  }
};

class Coulomb : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override { return "dry (Coulomb) friction, constant against the motion"; }
  std::string term() const override { return "Fc·sgn(qd)  (sgn smoothed as tanh(qd/velocity_smoothing))"; }
  std::string residualPattern() const override { return "jumps by a constant step whenever the motion reverses"; }
  bool appliesTo(ModelKind kind) const override { return kind != ModelKind::JointTracking; }
  std::vector<std::string> requiredSignals() const override { return {"qd"}; }
  std::vector<std::string> parameterNames() const override { return {"Fc"}; }
  void regressor(const Dataset& data, int c, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    const auto& qd = data.signal("qd", c);
    for (Eigen::Index k = 0; k < qd.size(); ++k) columns(k, 0) = sgn(data, qd[k]);
  }
  std::vector<double> typicalParameters(ModelKind, int c) const override { return {typical(kCoulomb, c)}; }
};

class Viscous : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override { return "viscous friction of the lubricated gear and bearings"; }
  std::string term() const override { return "Fv·qd"; }
  std::string residualPattern() const override { return "grows linearly with the joint speed"; }
  bool appliesTo(ModelKind kind) const override { return kind == ModelKind::JointCurrent; }
  std::vector<std::string> requiredSignals() const override { return {"qd"}; }
  std::vector<std::string> parameterNames() const override { return {"Fv"}; }
  void regressor(const Dataset& data, int c, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    columns.col(0) = data.signal("qd", c);
  }
  std::vector<double> typicalParameters(ModelKind, int c) const override { return {typical(kViscous, c)}; }
};

class Stribeck : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override {
    return "breakaway friction above the Coulomb level at low speed (Stribeck effect of lubricated contacts)";
  }
  std::string term() const override { return "Fs·exp(-(qd/vs)^2)·sgn(qd), vs searched"; }
  std::string residualPattern() const override {
    return "peaks just after the motion starts or reverses and fades as the joint speeds up";
  }
  bool appliesTo(ModelKind kind) const override { return kind == ModelKind::JointCurrent; }
  std::vector<std::string> requiredSignals() const override { return {"qd"}; }
  std::vector<std::string> parameterNames() const override { return {"Fs"}; }
  std::optional<NonlinearParameter> nonlinearParameter() const override {
    NonlinearParameter p{"stribeck_velocity", "rad/s", {}, false};
    for (int i = 0; i <= 32; ++i) p.grid.push_back(0.002 * std::pow(250.0, i / 32.0));  // 0.002 .. 0.5 rad/s
    return p;
  }
  void regressor(const Dataset& data, int c, double vs, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    const auto& qd = data.signal("qd", c);
    for (Eigen::Index k = 0; k < qd.size(); ++k) {
      const double ratio = qd[k] / vs;
      columns(k, 0) = std::exp(-ratio * ratio) * sgn(data, qd[k]);
    }
  }
  std::vector<double> typicalParameters(ModelKind, int c) const override { return {0.5 * typical(kCoulomb, c)}; }
  double typicalNonlinear(int) const override { return 0.03; }
};

class LoadFriction : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override {
    return "friction that rises with the transmitted load (Harmonic Drive force-transfer law, linear + parabolic)";
  }
  std::string term() const override { return "(mu1·|tau| + mu2·tau^2)·sgn(qd)"; }
  std::string residualPattern() const override { return "grows with |load torque| in both directions"; }
  bool appliesTo(ModelKind kind) const override { return kind != ModelKind::JointTracking; }
  std::vector<std::string> requiredSignals() const override { return {"tau", "qd"}; }
  std::vector<std::string> parameterNames() const override { return {"mu1", "mu2"}; }
  void regressor(const Dataset& data, int c, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    const auto& tau = data.signal("tau", c);
    const auto& qd = data.signal("qd", c);
    for (Eigen::Index k = 0; k < tau.size(); ++k) {
      const double s = sgn(data, qd[k]);
      columns(k, 0) = std::abs(tau[k]) * s;
      columns(k, 1) = tau[k] * tau[k] * s;
    }
  }
  std::vector<double> typicalParameters(ModelKind, int c) const override {
    const double scale = typical(kTorqueScale, c);
    return {0.15 * typical(kCoulomb, c) / scale, 0.1 * typical(kCoulomb, c) / (scale * scale)};
  }
};

class DirectionAsymmetry : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override {
    return "friction differs between DIRECT (motoring, load and motion in the same sense) and INDIRECT "
           "(regenerating) power flow";
  }
  std::string term() const override { return "dFc·sgn(qd)·[tau·qd >= 0]"; }
  std::string residualPattern() const override {
    return "differs between motoring (load torque and motion in the same sense) and regenerating phases";
  }
  bool appliesTo(ModelKind kind) const override { return kind != ModelKind::JointTracking; }
  std::vector<std::string> requiredSignals() const override { return {"tau", "qd"}; }
  std::vector<std::string> parameterNames() const override { return {"dFc"}; }
  void regressor(const Dataset& data, int c, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    const auto& tau = data.signal("tau", c);
    const auto& qd = data.signal("qd", c);
    for (Eigen::Index k = 0; k < tau.size(); ++k) columns(k, 0) = tau[k] * qd[k] >= 0.0 ? sgn(data, qd[k]) : 0.0;
  }
  std::vector<double> typicalParameters(ModelKind, int c) const override { return {0.3 * typical(kCoulomb, c)}; }
};

class TemperatureFriction : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override { return "friction falls as the joints warm up (lubricant viscosity)"; }
  std::string term() const override { return "(a·sgn(qd) + b·qd)·(T - T0)"; }
  std::string residualPattern() const override { return "drifts as the joint temperature changes"; }
  bool appliesTo(ModelKind kind) const override { return kind == ModelKind::JointCurrent; }
  std::vector<std::string> requiredSignals() const override { return {"temperature", "qd"}; }
  std::vector<std::string> parameterNames() const override { return {"a", "b"}; }
  void regressor(const Dataset& data, int c, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    const auto& temperature = data.signal("temperature", c);
    const auto& qd = data.signal("qd", c);
    const double reference = data.settings().referenceTemperature;
    for (Eigen::Index k = 0; k < qd.size(); ++k) {
      const double warming = temperature[k] - reference;
      columns(k, 0) = sgn(data, qd[k]) * warming;
      columns(k, 1) = qd[k] * warming;
    }
  }
  std::vector<double> typicalParameters(ModelKind, int c) const override {
    return {-0.02 * typical(kCoulomb, c), -0.01 * typical(kViscous, c)};
  }
};

class RotorInertia : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override { return "inertia of the motor rotor reflected through the gear ratio"; }
  std::string term() const override { return "Ir·qdd"; }
  std::string residualPattern() const override { return "follows the joint acceleration"; }
  bool appliesTo(ModelKind kind) const override { return kind == ModelKind::JointCurrent; }
  std::vector<std::string> requiredSignals() const override { return {"qdd"}; }
  std::vector<std::string> parameterNames() const override { return {"Ir"}; }
  void regressor(const Dataset& data, int c, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    columns.col(0) = data.signal("qdd", c);
  }
  std::vector<double> typicalParameters(ModelKind, int c) const override {
    return {typical(kRotorInertia, c) * typical(kDriveGain, c)};
  }
};

class TrackingDelay : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override { return "controller and servo lag: the joint follows its target late"; }
  std::string term() const override {
    return "actual(t) = target(t - d)  (scale·[target(t-d) - target(t)]), d searched";
  }
  std::string residualPattern() const override {
    return "follows the commanded joint speed with the opposite sign: the actual position lags the target";
  }
  bool appliesTo(ModelKind kind) const override { return kind == ModelKind::JointTracking; }
  std::vector<std::string> requiredSignals() const override { return {"target_q", "target_qd", "time"}; }
  std::vector<std::string> parameterNames() const override { return {"scale"}; }
  std::optional<NonlinearParameter> nonlinearParameter() const override {
    NonlinearParameter p{"delay", "s", {}, false};
    for (int i = 0; i <= 50; ++i) p.grid.push_back(0.002 * i);  // 0 .. 100 ms
    return p;
  }
  // target(t - d) by cubic Hermite interpolation of target_q with its velocity target_qd.
  void regressor(const Dataset& data, int c, double delay, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    const auto& time = data.signal("time", c);
    const auto& position = data.signal("target_q", c);
    const auto& velocity = data.signal("target_qd", c);
    const Eigen::Index n = time.size();
    Eigen::Index segment = 0;
    for (Eigen::Index k = 0; k < n; ++k) {
      const double t = time[k] - delay;
      double shifted;
      if (t <= time[0]) {
        shifted = position[0] + velocity[0] * (t - time[0]);
      } else {
        while (segment + 2 < n && time[segment + 1] < t) ++segment;
        const double h = time[segment + 1] - time[segment];
        const double s = std::min(1.0, (t - time[segment]) / h);
        const double s2 = s * s, s3 = s2 * s;
        shifted = (2 * s3 - 3 * s2 + 1) * position[segment] + (s3 - 2 * s2 + s) * h * velocity[segment] +
                  (-2 * s3 + 3 * s2) * position[segment + 1] + (s3 - s2) * h * velocity[segment + 1];
      }
      columns(k, 0) = shifted - position[k];
    }
  }
  std::vector<double> typicalParameters(ModelKind, int) const override { return {1.0}; }
  double typicalNonlinear(int) const override { return 0.008; }
};

template <typename T>
EffectFactory factory() {
  return [](const EffectSpec& spec) { return std::make_unique<T>(spec); };
}

}  // namespace

double typicalDriveGain(int channel) { return typical(kDriveGain, channel); }
double typicalCoulomb(int channel) { return typical(kCoulomb, channel); }
double typicalViscous(int channel) { return typical(kViscous, channel); }
double smoothedDirection(const Dataset& data, double velocity) {
  return smoothSign(velocity, data.settings().velocitySmoothing);
}
std::vector<bool> runBeginnings(const Dataset& data, Eigen::Index samples) {
  std::vector<bool> begins(static_cast<std::size_t>(samples), false);
  if (samples > 0) begins.front() = true;
  for (Eigen::Index start : data.runStarts()) {
    if (start < samples) begins[static_cast<std::size_t>(start)] = true;
  }
  return begins;
}

const std::vector<CatalogueEntry>& catalogueTable() {
  static const std::vector<CatalogueEntry> table{
      {"rigid_body", factory<RigidBody>()},
      {"drive_gain", factory<DriveGain>()},
      {"offset", factory<Offset>()},
      {"coulomb", factory<Coulomb>()},
      {"viscous", factory<Viscous>()},
      {"stribeck", factory<Stribeck>()},
      {"load_friction", factory<LoadFriction>()},
      {"direction_asymmetry", factory<DirectionAsymmetry>()},
      {"temperature_friction", factory<TemperatureFriction>()},
      {"dahl_friction", dahlFrictionFactory()},
      {"maxwell_slip", maxwellSlipFrictionFactory()},
      {"position_ripple", positionRippleFactory()},
      {"payload", payloadFactory()},
      {"rotor_inertia", factory<RotorInertia>()},
      {"tracking_delay", factory<TrackingDelay>()},
  };
  return table;
}

}  // namespace arcplan::model::detail
