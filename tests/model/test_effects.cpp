// The model file, the effect catalogue (each regressor against its formula), nonlinear parameter
// searches, user effects (registered C++ class and muparser expressions), and least-squares fits
// that must recover parameters put into synthetic data by formulas written here.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/model/dataset.h"
#include "arcplan/model/effect.h"
#include "arcplan/model/fitting.h"
#include "arcplan/model/model_spec.h"
#include "arcplan/robot/dynamics.h"
#include "model/model_test_support.h"
#include "support/error_message.h"

namespace {

using arcplan::testing::errorMessageOf;
using arcplan::testing::jointCurrentModel;
using arcplan::testing::regressorColumns;

using namespace arcplan::model;
using arcplan::Error;

TEST(ModelFile, ParsesTheBaseModelOfTheIssue) {
  const auto spec = parseModelYaml(
      "kind: joint_current          # predict actual_current_j from the motion\n"
      "load_torque: target_moment\n"
      "effects: [drive_gain, offset, coulomb, viscous]\n",
      "base.yaml");
  EXPECT_EQ(spec.kind, ModelKind::JointCurrent);
  EXPECT_EQ(spec.loadTorque, LoadTorqueSource::TargetMoment);
  ASSERT_EQ(spec.effects.size(), 4u);
  EXPECT_EQ(spec.effects[2].id, "coulomb");
  EXPECT_TRUE(spec.effects[2].joints.empty());
}

TEST(ModelFile, ParsesJointsOptionsExpressionsAndRoundTripsWithParameters) {
  auto spec = parseModelYaml(
      "kind: joint_current\n"
      "load_torque: rigid_body\n"
      "payload: {mass: 1.5, center_of_mass: [0, 0, 0.1]}\n"
      "effects:\n"
      "  - drive_gain\n"
      "  - coulomb:1,2\n"
      "  - {id: stribeck, joints: [0], stribeck_velocity: 0.05}\n"
      "  - {id: position_ripple, harmonics: 2}\n"
      "  - {id: drag, expression: \"qd*abs(qd)\", explanation: oil churning}\n",
      "m.yaml");
  EXPECT_EQ(spec.loadTorque, LoadTorqueSource::RigidBody);
  EXPECT_DOUBLE_EQ(spec.dynamics.payload.mass, 1.5);
  EXPECT_EQ(spec.effects[1].joints, (std::vector<int>{1, 2}));
  EXPECT_DOUBLE_EQ(spec.effects[2].options.at("stribeck_velocity"), 0.05);
  EXPECT_EQ(createEffect(spec.effects[3])->parameterNames().size(), 4u);
  EXPECT_EQ(spec.effects[4].expressions, (std::vector<std::string>{"qd*abs(qd)"}));
  spec.effects[1].parameters["Fc"] = {std::nan(""), 0.7, 0.4};
  const auto back = parseModelYaml(toYaml(spec), "back.yaml");
  ASSERT_EQ(back.effects.size(), 5u);
  EXPECT_EQ(back.effects[1].joints, (std::vector<int>{1, 2}));
  EXPECT_TRUE(std::isnan(back.effects[1].parameters.at("Fc")[0]));
  EXPECT_DOUBLE_EQ(back.effects[1].parameters.at("Fc")[1], 0.7);
  EXPECT_DOUBLE_EQ(back.effects[2].options.at("stribeck_velocity"), 0.05);
  EXPECT_EQ(back.effects[4].explanation, "oil churning");
  EXPECT_DOUBLE_EQ(back.dynamics.payload.centerOfMass.z(), 0.1);
}

TEST(ModelFile, TheRobotIsArcplansUr10eOrTheUrdfItNames) {
  const auto named = parseModelYaml("kind: joint_current\nrobot: {urdf: arms/ur5.urdf}\neffects: []\n", "/m/x.yaml");
  EXPECT_EQ(named.urdf, std::filesystem::path("/m/arms/ur5.urdf"));  // relative to the model file
  EXPECT_NE(toYaml(named).find("robot: {urdf: /m/arms/ur5.urdf}"), std::string::npos) << toYaml(named);
  EXPECT_TRUE(parseModelYaml("kind: joint_current\nrobot: ur10e\neffects: []\n", "m.yaml").urdf.empty());
  const auto other = errorMessageOf([] { parseModelYaml("kind: joint_current\nrobot: ur5\neffects: []\n", "m.yaml"); });
  EXPECT_NE(other.find("m.yaml:2:8: robot: expected 'ur10e' (built in) or a mapping {urdf: FILE}"), std::string::npos)
      << other;
  const auto missing = parseModelYaml("kind: joint_current\nrobot: {urdf: /no/such.urdf}\neffects: []\n", "m.yaml");
  EXPECT_NE(errorMessageOf([&] { modelRobot(missing); }).find("/no/such.urdf does not exist"), std::string::npos);
}

TEST(ModelFile, BadFilesNameTheFieldAndWhatWasExpected) {
  const auto unknownEffect = errorMessageOf([] { jointCurrentModel("drive_gain, frobnication"); });
  EXPECT_NE(unknownEffect.find("unknown effect 'frobnication'"), std::string::npos) << unknownEffect;
  EXPECT_NE(unknownEffect.find("load_friction"), std::string::npos);  // lists the known ones
  EXPECT_NE(unknownEffect.find("m.yaml"), std::string::npos);
  EXPECT_NE(errorMessageOf([] {
              parseModelYaml("kind: joint_torque\neffects: []\n", "k.yaml");
            }).find("unknown kind 'joint_torque'"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([] {
              parseModelYaml("kind: joint_current\neffect: []\n", "k.yaml");
            }).find("unknown key 'effect'"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([] {
              parseModelYaml("kind: joint_tracking\neffects: [coulomb]\n", "k.yaml");
            }).find("does not apply to kind joint_tracking"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([] { jointCurrentModel("{id: stribeck, width: 2}"); }).find("unknown option 'width'"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([] { jointCurrentModel("coulomb, coulomb"); }).find("listed twice"), std::string::npos);
  EXPECT_NE(errorMessageOf([] { parseModelYaml("kind: [\n", "bad.yaml"); }).find("bad.yaml:"), std::string::npos);
  EXPECT_NE(errorMessageOf([] { parseEffectArgument("coulomb:1,x"); }).find("not a finite number"), std::string::npos);
}

class CatalogueOnSyntheticLog : public ::testing::Test {
protected:
  void SetUp() override {
    motion = arcplan::testing::makeMotionLog(2000, 200.0);
    spec = jointCurrentModel("");
    data = std::make_unique<Dataset>(makeJointDataset(motion.log, spec));
  }
  arcplan::testing::MotionLog motion;
  ModelSpec spec;
  std::unique_ptr<Dataset> data;
};

TEST_F(CatalogueOnSyntheticLog, FrictionRegressorsFollowTheirFormulas) {
  const int j = 2;
  const auto& qd = motion.log.vectors["actual_qd"];
  const auto& tau = motion.log.vectors["target_moment"];
  const auto& temperature = motion.log.vectors["joint_temperatures"];
  const double width = spec.velocitySmoothing;
  const auto coulomb = regressorColumns("coulomb", *data, j);
  const auto viscous = regressorColumns("viscous", *data, j);
  const auto stribeck = regressorColumns("stribeck", *data, j, 0.05);
  const auto load = regressorColumns("load_friction", *data, j);
  const auto asymmetry = regressorColumns("direction_asymmetry", *data, j);
  const auto warming = regressorColumns("temperature_friction", *data, j);
  const auto gain = regressorColumns("drive_gain", *data, j);
  const auto offset = regressorColumns("offset", *data, j);
  for (Eigen::Index k = 0; k < qd.rows(); k += 37) {
    const double s = std::tanh(qd(k, j) / width);
    EXPECT_DOUBLE_EQ(coulomb(k, 0), s);
    EXPECT_DOUBLE_EQ(viscous(k, 0), qd(k, j));
    EXPECT_NEAR(stribeck(k, 0), std::exp(-std::pow(qd(k, j) / 0.05, 2)) * s, 1e-15);
    EXPECT_NEAR(load(k, 0), std::abs(tau(k, j)) * s, 1e-12);
    EXPECT_NEAR(load(k, 1), tau(k, j) * tau(k, j) * s, 1e-9);
    EXPECT_DOUBLE_EQ(asymmetry(k, 0), tau(k, j) * qd(k, j) >= 0 ? s : 0.0);
    EXPECT_NEAR(warming(k, 0), s * (temperature(k, j) - 25.0), 1e-12);
    EXPECT_NEAR(warming(k, 1), qd(k, j) * (temperature(k, j) - 25.0), 1e-12);
    EXPECT_DOUBLE_EQ(gain(k, 0), tau(k, j));
    EXPECT_DOUBLE_EQ(offset(k, 0), 1.0);
  }
}

TEST_F(CatalogueOnSyntheticLog, AccelerationIsDerivedWithoutLagAndDrivesRotorInertia) {
  const auto rotor = regressorColumns("rotor_inertia", *data, 1);
  double worst = 0.0, scale = 0.0;
  for (Eigen::Index k = 50; k < rotor.rows() - 50; ++k) {
    worst = std::max(worst, std::abs(rotor(k, 0) - motion.qdd(k, 1)));
    scale = std::max(scale, std::abs(motion.qdd(k, 1)));
  }
  EXPECT_LT(worst, 0.01 * scale);
}

TEST_F(CatalogueOnSyntheticLog, PositionRippleIsACosineAndSineSeriesInTheJointAngle) {
  EffectSpec rippleSpec;
  rippleSpec.id = "position_ripple";
  rippleSpec.options["harmonics"] = 2;
  const Eigen::MatrixXd columns = regressorColumns(rippleSpec, *data, 0, 12.0);
  ASSERT_EQ(columns.cols(), 4);
  const auto& q = motion.log.vectors["actual_q"];
  for (Eigen::Index k = 0; k < q.rows(); k += 101) {
    EXPECT_NEAR(columns(k, 0), std::cos(12.0 * q(k, 0)), 1e-12);
    EXPECT_NEAR(columns(k, 1), std::sin(12.0 * q(k, 0)), 1e-12);
    EXPECT_NEAR(columns(k, 2), std::cos(24.0 * q(k, 0)), 1e-12);
    EXPECT_NEAR(columns(k, 3), std::sin(24.0 * q(k, 0)), 1e-12);
  }
}

TEST_F(CatalogueOnSyntheticLog, RigidBodyAndPayloadColumnsComeFromTheUr10eDynamics) {
  const auto& model = arcplan::robot::ur10e();
  arcplan::robot::DynamicsData dynamics(model);
  const auto rigid = regressorColumns("rigid_body", *data, 1);
  const auto payload = regressorColumns("payload", *data, 1);
  const Eigen::Index k = 777;
  Eigen::VectorXd q(6), qd(6), qdd(6);
  for (int j = 0; j < 6; ++j) {
    q[j] = motion.log.vectors["actual_q"](k, j);
    qd[j] = motion.log.vectors["actual_qd"](k, j);
    qdd[j] = data->signal("qdd", j)[k];
  }
  EXPECT_NEAR(rigid(k, 0), arcplan::robot::gravityTorque(model, q, dynamics)[1], 1e-9);
  EXPECT_NEAR(rigid(k, 0) + rigid(k, 1), arcplan::robot::inverseDynamics(model, q, qd, qdd, dynamics)[1], 1e-9);
  // A 2 kg mass at the tool origin adds exactly 2·(first payload column) to the joint torque.
  arcplan::robot::DynamicsParameters withMass;
  withMass.payload.mass = 2.0;
  const double added = arcplan::robot::inverseDynamics(model, q, qd, qdd, dynamics, withMass)[1] -
                       arcplan::robot::inverseDynamics(model, q, qd, qdd, dynamics)[1];
  EXPECT_NEAR(2.0 * payload(k, 0), added, 1e-9);
}

TEST(NonlinearSearch, FindsTheRippleFrequencyTheStribeckVelocityAndTheDelay) {
  auto motion = arcplan::testing::makeMotionLog(6000, 250.0);
  const auto spec = jointCurrentModel("");
  const Dataset data = makeJointDataset(motion.log, spec);
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 0.02);
  const auto& q = motion.log.vectors["actual_q"];
  const auto& qd = motion.log.vectors["actual_qd"];
  Eigen::VectorXd ripple(q.rows()), stribeck(q.rows());
  for (Eigen::Index k = 0; k < q.rows(); ++k) {
    ripple[k] = 0.1 * std::cos(137.0 * q(k, 3)) - 0.05 * std::sin(137.0 * q(k, 3)) + noise(random);
    stribeck[k] = 0.3 * std::exp(-std::pow(qd(k, 3) / 0.04, 2)) * std::tanh(qd(k, 3) / 0.01) + noise(random);
  }
  EffectSpec rippleSpec{"position_ripple", {}, {}, "", {}, {}, {}};
  EXPECT_EQ(createEffect(rippleSpec)->searchNonlinear(data, 3, ripple), 137.0);
  EffectSpec stribeckSpec{"stribeck", {}, {}, "", {}, {}, {}};
  EXPECT_NEAR(createEffect(stribeckSpec)->searchNonlinear(data, 3, stribeck), 0.04, 0.002);

  // Tracking: actual = target delayed by 12 ms, evaluated in closed form.
  auto tracking = motion.log;
  tracking.vectors["target_q"] = tracking.vectors["actual_q"];
  tracking.vectors["target_qd"] = tracking.vectors["actual_qd"];
  Eigen::MatrixXd actual = tracking.vectors["actual_q"];
  const double delay = 0.012;
  auto delayedMotion = arcplan::testing::makeMotionLog(6000, 250.0, -delay);
  actual = delayedMotion.log.vectors["actual_q"];
  tracking.vectors["actual_q"] = actual;
  const auto trackingSpec = parseModelYaml("kind: joint_tracking\neffects: []\n", "t.yaml");
  const Dataset trackingData = makeJointDataset(tracking, trackingSpec);
  const Eigen::VectorXd lag = trackingData.measured(2) - trackingData.basePrediction(2);
  EffectSpec delaySpec{"tracking_delay", {}, {}, "", {}, {}, {}};
  EXPECT_NEAR(createEffect(delaySpec)->searchNonlinear(trackingData, 2, lag), delay, 1e-5);
}

// A user effect written in C++ and registered by name: cubic drag, c·qd³.
class CubicDrag : public Effect {
public:
  using Effect::Effect;
  std::string meaning() const override { return "drag growing with the cube of the speed"; }
  std::string term() const override { return "c·qd^3"; }
  std::string residualPattern() const override { return "grows with the cube of the speed"; }
  bool appliesTo(ModelKind kind) const override { return kind == ModelKind::JointCurrent; }
  std::vector<std::string> requiredSignals() const override { return {"qd"}; }
  std::vector<std::string> parameterNames() const override { return {"c"}; }
  void regressor(const Dataset& data, int channel, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    columns.col(0) = data.signal("qd", channel).array().cube().matrix();
  }
};

TEST(UserEffects, RegisteredClassAndExpressionAreFittedLikeCatalogueEffects) {
  if (!isRegisteredEffect("cubic_drag")) {
    registerEffect("cubic_drag", [](const EffectSpec& s) { return std::make_unique<CubicDrag>(s); });
  }
  EXPECT_NE(errorMessageOf([] {
              registerEffect("coulomb", [](const EffectSpec& s) { return std::make_unique<CubicDrag>(s); });
            }).find("already registered"),
            std::string::npos);
  auto motion = arcplan::testing::makeMotionLog(3000, 200.0);
  const auto& qd = motion.log.vectors["actual_qd"];
  const auto& q = motion.log.vectors["actual_q"];
  auto& current = motion.log.vectors["actual_current"];
  for (Eigen::Index k = 0; k < qd.rows(); ++k) {
    for (int j = 0; j < 6; ++j)
      current(k, j) = 0.3 * std::pow(qd(k, j), 3) - 0.2 * qd(k, j) * std::abs(qd(k, j)) + 0.1 * q(k, 1);
  }
  const auto spec =
      jointCurrentModel("cubic_drag, {id: drag, expression: \"qd*abs(qd)\"}, {id: coupling, expression: \"q_1\"}");
  const Dataset data = makeJointDataset(motion.log, spec);
  const auto fitted = fitModel(spec, data);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(fitted.effects[0].values[j][0], 0.3, 1e-9) << "joint " << j;
    EXPECT_NEAR(fitted.effects[1].values[j][0], -0.2, 1e-9);
    EXPECT_NEAR(fitted.effects[2].values[j][0], 0.1, 1e-9);
  }
  const auto unknown = errorMessageOf([&] {
    const auto bad = jointCurrentModel("{id: broken, expression: \"qd*torque\"}");
    fitModel(bad, makeJointDataset(motion.log, bad));
  });
  EXPECT_NE(unknown.find("synthetic: effect 'broken': expression 'qd*torque' needs signal 'torque'"), std::string::npos)
      << unknown;
  EXPECT_NE(errorMessageOf([] { jointCurrentModel("{id: bad, expression: \"qd*(\"}"); }).find("expression"),
            std::string::npos);
}

TEST(Fitting, RecoversParametersWithHonestStandardErrors) {
  // current = k·tau + c + Fc·sgn(qd) + Fv·qd + mu2·tau²·sgn(qd) + noise, built here from the formulas.
  auto motion = arcplan::testing::makeMotionLog(8000, 250.0);
  const auto& qd = motion.log.vectors["actual_qd"];
  const auto& tau = motion.log.vectors["target_moment"];
  auto& current = motion.log.vectors["actual_current"];
  std::mt19937 random(21);
  const double sigma = 0.03;
  std::normal_distribution<double> noise(0.0, sigma);
  const double k = 0.09, c = -0.04, fc = 0.8, fv = 0.6, mu2 = 2e-4;
  for (Eigen::Index i = 0; i < qd.rows(); ++i) {
    for (int j = 0; j < 6; ++j) {
      const double s = std::tanh(qd(i, j) / 0.01);
      current(i, j) = k * tau(i, j) + c + fc * s + fv * qd(i, j) + mu2 * tau(i, j) * tau(i, j) * s + noise(random);
    }
  }
  const auto spec = jointCurrentModel("drive_gain, offset, coulomb, viscous, load_friction");
  const Dataset data = makeJointDataset(motion.log, spec);
  const auto fitted = fitModel(spec, data);
  const std::vector<std::pair<int, double>> truth{{0, k}, {1, c}, {2, fc}, {3, fv}};
  int outsideThreeSigma = 0, checked = 0;
  for (int j = 0; j < 6; ++j) {
    for (const auto& [effect, value] : truth) {
      const double estimate = fitted.effects[effect].values[j][0];
      const double error = fitted.effects[effect].standardErrors[j][0];
      EXPECT_GT(error, 0.0);
      EXPECT_LT(error, 0.05 * std::abs(value));
      outsideThreeSigma += std::abs(estimate - value) > 3.0 * error;
      ++checked;
    }
    EXPECT_NEAR(fitted.effects[4].values[j][1], mu2, 4.0 * fitted.effects[4].standardErrors[j][1]);
  }
  EXPECT_LE(outsideThreeSigma, 1) << "of " << checked;  // 3σ misses are 0.3 % events
  const auto prediction = predict(fitted, data, 4);
  const double rmse = std::sqrt((data.measured(4) - prediction).squaredNorm() / prediction.size());
  EXPECT_NEAR(rmse, sigma, 0.1 * sigma);
}

TEST(Fitting, EffectsOnMissingSignalsOrJointsAreErrors) {
  auto motion = arcplan::testing::makeMotionLog(500, 100.0);
  motion.log.vectors.erase("joint_temperatures");
  const auto warm = jointCurrentModel("temperature_friction");
  const auto message = errorMessageOf([&] { fitModel(warm, makeJointDataset(motion.log, warm)); });
  EXPECT_NE(message.find("temperature"), std::string::npos) << message;
  const auto far = jointCurrentModel("coulomb:7");
  EXPECT_NE(errorMessageOf([&] { fitModel(far, makeJointDataset(motion.log, far)); }).find("joint 7 does not exist"),
            std::string::npos);
  auto spec = jointCurrentModel("offset");
  spec.joints = 7;
  EXPECT_NE(errorMessageOf([&] { fitModel(spec, makeJointDataset(motion.log, spec)); }).find("mismatched joint count"),
            std::string::npos);
}

}  // namespace
