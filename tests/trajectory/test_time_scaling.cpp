// TCP-speed time scaling on the thesis' straight line and on synthetic paths. Expected values come
// from the kinematics of a ramp–cruise–brake profile (L/v + rise time), the joint speed limits of
// the URDF and finite differences of the samples, never from the code under test.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/trajectory/time_scaling.h"
#include "straight_line.h"

namespace arcplan::trajectory {
namespace {

// |AB| of the thesis line: (0.1, 0.8, 0.21) m.
const double kLineLength = std::sqrt(0.1 * 0.1 + 0.8 * 0.8 + 0.21 * 0.21);

double peakSpeed(const TimedTrajectory& trajectory) {
  return *std::max_element(trajectory.tcpSpeed.begin(), trajectory.tcpSpeed.end());
}

double peakJointSpeedRatio(const TimedTrajectory& trajectory, const robot::Vector6& limits) {
  double ratio = 0.0;
  for (const auto& qd : trajectory.velocity) ratio = std::max(ratio, qd.cwiseAbs().cwiseQuotient(limits).maxCoeff());
  return ratio;
}

robot::Vector6 urdfSpeedLimits() {
  robot::Vector6 limits;
  for (int j = 0; j < 6; ++j) limits[j] = robot::ur10e().joints()[j].limits.velocity;
  return limits;
}

const JointPath& linePath() {
  static const JointPath path = testing::straightLinePath(robot::ur10e(), 200);
  return path;
}

TEST(TimeScaling, StraightLineStaysUnderTheCollaborativeLimit) {
  const TimedTrajectory trajectory = scaleToTcpSpeed(robot::ur10e(), linePath(), {});
  EXPECT_LE(peakSpeed(trajectory), 0.25);
  EXPECT_TRUE(std::none_of(trajectory.tcpSpeed.begin(), trajectory.tcpSpeed.end(), [](double v) { return v > 0.25; }));
  // Ramp up at constant acceleration over 0.2 s, cruise, brake over 0.2 s: each ramp costs half
  // its duration, so no trajectory with these limits is faster than L/v + rise time (3.532 s).
  const double ideal = kLineLength / 0.25 + 0.2;
  EXPECT_GE(trajectory.duration(), ideal - 1e-6);
  EXPECT_LE(trajectory.duration(), 3.55);  // thesis measured 3.5 s (with 0.26 m/s peaks)
  // Densified waypoints lie on joint-space chords between IK points of the line, micrometres off it.
  EXPECT_NEAR(trajectory.tcpPathLength, kLineLength, 1e-5);
  EXPECT_LE(peakJointSpeedRatio(trajectory, urdfSpeedLimits()), 1.0);
}

TEST(TimeScaling, RampCruiseBrakeProfile) {
  const TimedTrajectory trajectory = scaleToTcpSpeed(robot::ur10e(), linePath(), {});
  const auto speedAt = [&](double t) {
    const auto i = static_cast<std::size_t>(std::lround(t / (trajectory.time[1] - trajectory.time[0])));
    return trajectory.tcpSpeed[std::min(i, trajectory.tcpSpeed.size() - 1)];
  };
  EXPECT_LT(speedAt(0.0), 1e-9);
  EXPECT_LT(speedAt(trajectory.duration()), 1e-9);
  EXPECT_LT(trajectory.velocity.front().norm(), 1e-12);
  EXPECT_LT(trajectory.velocity.back().norm(), 1e-12);
  // Constant acceleration v/T_rise: half speed at half the rise time, on both ramps.
  EXPECT_NEAR(speedAt(0.1), 0.125, 0.01);
  EXPECT_NEAR(speedAt(trajectory.duration() - 0.1), 0.125, 0.01);
  // Cruise at the limit everywhere between the ramps.
  for (double t = 0.25; t < trajectory.duration() - 0.25; t += 0.05) {
    EXPECT_GT(speedAt(t), 0.25 * 0.998) << "t = " << t;
  }
}

TEST(TimeScaling, SamplesAreConsistentWithFiniteDifferencesAndKinematics) {
  const auto& model = robot::ur10e();
  const TimedTrajectory trajectory = scaleToTcpSpeed(model, linePath(), {});
  const std::size_t n = trajectory.time.size();
  ASSERT_GT(n, 1000u);
  ASSERT_EQ(trajectory.position.size(), n);
  ASSERT_EQ(trajectory.tcpPosition.size(), n);
  EXPECT_EQ(trajectory.time.front(), 0.0);
  EXPECT_DOUBLE_EQ(trajectory.time.back(), trajectory.duration());
  robot::KinematicsData kinematics(model);
  // Within one knot interval q is a cubic, so the corrected trapezoid rule
  // q1 − q0 = dt·(qd0 + qd1)/2 − dt²·(qdd1 − qdd0)/12 is exact, and so is the plain trapezoid rule
  // for qd (quadratic) from qdd (linear). Pairs straddling a knot are skipped: PCHIP's
  // acceleration jumps there.
  const auto intervalOf = [&](double t) {
    return std::upper_bound(trajectory.knotTimes.begin(), trajectory.knotTimes.end(), t) - trajectory.knotTimes.begin();
  };
  std::size_t pairsChecked = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const double dt = trajectory.time[i] - trajectory.time[i - 1];
    ASSERT_GT(dt, 0.0);
    ASSERT_LE(dt, 0.002 + 1e-12);
    if (i + 1 == n || intervalOf(trajectory.time[i]) != intervalOf(trajectory.time[i - 1])) continue;
    ++pairsChecked;
    const double chordSpeed = (trajectory.tcpPosition[i] - trajectory.tcpPosition[i - 1]).norm() / dt;
    EXPECT_NEAR(chordSpeed, 0.5 * (trajectory.tcpSpeed[i] + trajectory.tcpSpeed[i - 1]), 2e-4)
        << "t = " << trajectory.time[i];
    const robot::Vector6 jointRate = (trajectory.position[i] - trajectory.position[i - 1]) / dt;
    const robot::Vector6 trapezoid = 0.5 * (trajectory.velocity[i] + trajectory.velocity[i - 1]) -
                                     dt / 12.0 * (trajectory.acceleration[i] - trajectory.acceleration[i - 1]);
    EXPECT_LT((jointRate - trapezoid).norm(), 1e-8);
    const robot::Vector6 accelerationRate = (trajectory.velocity[i] - trajectory.velocity[i - 1]) / dt;
    EXPECT_LT((accelerationRate - 0.5 * (trajectory.acceleration[i] + trajectory.acceleration[i - 1])).norm(), 1e-6);
  }
  EXPECT_GT(pairsChecked, n / 3);
  for (std::size_t i = 0; i < n; i += 97) {
    robot::forwardKinematics(model, trajectory.position[i], kinematics);
    EXPECT_LT((kinematics.linkPoses[model.tipLink()].translation() - trajectory.tcpPosition[i]).norm(), 1e-12);
    // The straight line: every sample stays on A→B (within the 2 mm knot spacing's sagitta).
    const Eigen::Vector3d a = testing::thesisPoseA().translation(), b = testing::thesisPoseB().translation();
    const Eigen::Vector3d direction = (b - a).normalized();
    const Eigen::Vector3d offset = trajectory.tcpPosition[i] - a;
    EXPECT_LT((offset - offset.dot(direction) * direction).norm(), 1e-5);
  }
  EXPECT_EQ(trajectory.knotTimes.size(), trajectory.knots.size());
  EXPECT_EQ(trajectory.knots.front(), linePath().front());
  EXPECT_EQ(trajectory.knots.back(), linePath().back());
}

TEST(TimeScaling, MeanSpeedAtTheThesisSpeeds) {
  for (const double speed : {0.149, 0.200, 0.250}) {
    TimeScalingOptions options;
    options.maxTcpSpeed = speed;
    const TimedTrajectory trajectory = scaleToTcpSpeed(robot::ur10e(), linePath(), options);
    EXPECT_LE(peakSpeed(trajectory), speed);
    EXPECT_GE(trajectory.tcpPathLength / trajectory.duration(), 0.93 * speed) << "v_max " << speed;
    EXPECT_GE(trajectory.duration(), kLineLength / speed + 0.2 - 1e-6);
    EXPECT_LE(trajectory.duration(), kLineLength / speed + 0.2 + 0.01) << "v_max " << speed;
  }
}

TEST(TimeScaling, RiseTimeAndAccelerationLimit) {
  TimeScalingOptions slowRamp;
  slowRamp.riseTime = 0.6;
  const double slow = scaleToTcpSpeed(robot::ur10e(), linePath(), slowRamp).duration();
  EXPECT_GE(slow, kLineLength / 0.25 + 0.6 - 1e-6);
  EXPECT_LE(slow, kLineLength / 0.25 + 0.6 + 0.01);

  TimeScalingOptions accelerationLimited;
  accelerationLimited.riseTime = 5.0;            // ignored when an acceleration limit is given
  accelerationLimited.maxTcpAcceleration = 0.5;  // ramps of 0.25/0.5 = 0.5 s
  const TimedTrajectory trajectory = scaleToTcpSpeed(robot::ur10e(), linePath(), accelerationLimited);
  EXPECT_GE(trajectory.duration(), kLineLength / 0.25 + 0.5 - 1e-6);
  EXPECT_LE(trajectory.duration(), kLineLength / 0.25 + 0.5 + 0.01);
  const double dt = trajectory.time[1] - trajectory.time[0];
  const auto quarterRamp = static_cast<std::size_t>(std::lround(0.125 / dt));
  EXPECT_NEAR(trajectory.tcpSpeed[quarterRamp], 0.5 * 0.125, 0.005);
}

TEST(TimeScaling, JointSpeedLimitsSlowTheTcpDown) {
  // Shoulder pan alone, 1.2 rad: at 2 m/s allowed TCP speed the pan joint's 2.0944 rad/s limit is
  // what bounds the motion (the TCP is ~0.6 m from the axis: ~1.3 m/s).
  robot::Vector6 start = testing::thesisSeedA(), goal = start;
  goal[0] += 1.2;
  TimeScalingOptions options;
  options.maxTcpSpeed = 2.0;
  const TimedTrajectory trajectory = scaleToTcpSpeed(robot::ur10e(), {start, goal}, options);
  const robot::Vector6 limits = urdfSpeedLimits();
  const double ratio = peakJointSpeedRatio(trajectory, limits);
  EXPECT_LE(ratio, 1.0);
  EXPECT_GT(ratio, 0.97);  // the joint limit is reached, not avoided by a needlessly slow profile
  EXPECT_LT(peakSpeed(trajectory), 2.0);
  EXPECT_GE(trajectory.duration(), 1.2 / limits[0]);
}

TEST(TimeScaling, PureWristRotationTakesFiniteTime) {
  // tool0 lies on the wrist-3 axis: turning wrist 3 moves no TCP point, only the joint limit
  // (pi rad/s) bounds the motion.
  robot::Vector6 start = testing::thesisSeedA(), goal = start;
  goal[5] += 3.0;
  const TimedTrajectory trajectory = scaleToTcpSpeed(robot::ur10e(), {start, goal}, {});
  EXPECT_TRUE(std::isfinite(trajectory.duration()));
  EXPECT_GE(trajectory.duration(), 3.0 / M_PI);
  EXPECT_LT(trajectory.duration(), 10.0);
  EXPECT_LE(peakJointSpeedRatio(trajectory, urdfSpeedLimits()), 1.0);
  EXPECT_LT(peakSpeed(trajectory), 1e-9);
  EXPECT_NEAR(trajectory.position.back()[5], goal[5], 1e-12);
}

TEST(TimeScaling, TinyTwoWaypointMotion) {
  // One densification step only (1 mrad): still a rest-to-rest motion within the limits.
  robot::Vector6 start = testing::thesisSeedA(), goal = start;
  goal[0] += 0.001;
  const TimedTrajectory trajectory = scaleToTcpSpeed(robot::ur10e(), {start, goal}, {});
  EXPECT_GT(trajectory.duration(), 0.0);
  EXPECT_LT(trajectory.duration(), 0.5);
  EXPECT_LE(peakSpeed(trajectory), 0.25);
  EXPECT_EQ(trajectory.position.back(), goal);
  EXPECT_LT(trajectory.velocity.back().norm(), 1e-12);
}

TEST(TimeScaling, SparseRrtLikePathRespectsTheLimits) {
  robot::Vector6 a = testing::thesisSeedA(), m1, m2, b;
  m1 << -0.6, -1.9, 2.0, -1.5, -1.2, -0.2;
  m2 << 0.1, -1.3, 1.6, -2.2, -1.9, 0.9;
  b << 0.399, -1.624, 2.012, -1.958, -1.571, 0.399;
  const JointPath sparse{a, m1, m2, b};
  for (const double speed : {0.149, 0.25}) {
    TimeScalingOptions options;
    options.maxTcpSpeed = speed;
    const TimedTrajectory trajectory = scaleToTcpSpeed(robot::ur10e(), sparse, options);
    EXPECT_LE(peakSpeed(trajectory), speed);
    EXPECT_LE(peakJointSpeedRatio(trajectory, urdfSpeedLimits()), 1.0);
    EXPECT_GE(trajectory.tcpPathLength / trajectory.duration(), 0.85 * speed);
    // PCHIP never leaves the joint box of the two knots around a sample, so the motion stays
    // within one densification step of the planner's joint segments.
    std::size_t k = 0;
    for (std::size_t i = 0; i < trajectory.time.size(); ++i) {
      while (k + 2 < trajectory.knotTimes.size() && trajectory.time[i] >= trajectory.knotTimes[k + 1]) ++k;
      const robot::Vector6 low = trajectory.knots[k].cwiseMin(trajectory.knots[k + 1]);
      const robot::Vector6 high = trajectory.knots[k].cwiseMax(trajectory.knots[k + 1]);
      ASSERT_TRUE((trajectory.position[i].array() >= low.array() - 1e-12).all()) << "t = " << trajectory.time[i];
      ASSERT_TRUE((trajectory.position[i].array() <= high.array() + 1e-12).all()) << "t = " << trajectory.time[i];
    }
    EXPECT_EQ(trajectory.position.back(), b);
  }
}

// The thesis line and three sparse RRT-like paths through the same configurations.
std::vector<JointPath> lineAndSparsePaths() {
  robot::Vector6 m1, m2, b;
  m1 << -0.6, -1.9, 2.0, -1.5, -1.2, -0.2;
  m2 << 0.1, -1.3, 1.6, -2.2, -1.9, 0.9;
  b << 0.399, -1.624, 2.012, -1.958, -1.571, 0.399;
  return {linePath(), JointPath{testing::thesisSeedA(), m1, m2, b}, JointPath{m1, b},
          JointPath{b, m2, testing::thesisSeedA()}};
}

// The planned profile's duration bounds the scaled duration from below, and closely: on the thesis line and on sparse
// RRT-like paths at both thesis speeds, between the time the scaled motion's own TCP path needs at the limit plus one
// rise time (length / v + rise time, a profile's least) less 1 % and the scaled duration itself.
TEST(TimeScaling, PlannedDurationBoundsTheScaledOneFromBelow) {
  for (const JointPath& path : lineAndSparsePaths()) {
    for (const double speed : {0.149, 0.25}) {
      TimeScalingOptions options;
      options.maxTcpSpeed = speed;
      const TimedTrajectory scaled = scaleToTcpSpeed(robot::ur10e(), path, options);
      const double planned = plannedDuration(robot::ur10e(), path, options);
      EXPECT_LE(planned, scaled.duration() * (1.0 + 1e-12));
      EXPECT_GE(planned, 0.99 * (scaled.tcpPathLength / speed + options.riseTime));
      EXPECT_GE(planned, 0.98 * scaled.duration());
    }
  }
}

// scaledDuration is the full scaling's duration, to the bit (the same computation without the samples kept), on the
// thesis line and sparse RRT-like paths at both thesis speeds and the joint-limited 1 m/s; it refuses what the full
// scaling refuses.
TEST(TimeScaling, ScaledDurationIsTheFullScalingsDuration) {
  for (const JointPath& path : lineAndSparsePaths()) {
    for (const double speed : {0.149, 0.25, 1.0}) {
      TimeScalingOptions options;
      options.maxTcpSpeed = speed;
      EXPECT_EQ(scaledDuration(robot::ur10e(), path, options),
                scaleToTcpSpeed(robot::ur10e(), path, options).duration())
          << speed;
    }
  }
  TimeScalingOptions bad;
  bad.maxTcpSpeed = 0.0;
  EXPECT_THROW(scaledDuration(robot::ur10e(), linePath(), bad), Error);
  EXPECT_THROW(scaledDuration(robot::ur10e(), JointPath{testing::thesisSeedA()}, {}), Error);
}

std::string scalingError(const JointPath& path, const TimeScalingOptions& options) {
  try {
    scaleToTcpSpeed(robot::ur10e(), path, options);
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}

TEST(TimeScaling, RejectsBadOptions) {
  const auto withOption = [](auto change) {
    TimeScalingOptions options;
    change(options);
    return scalingError(linePath(), options);
  };
  EXPECT_NE(withOption([](auto& o) { o.maxTcpSpeed = 0.0; }).find("maxTcpSpeed"), std::string::npos);
  EXPECT_NE(withOption([](auto& o) { o.maxTcpSpeed = -0.25; }).find("maxTcpSpeed"), std::string::npos);
  EXPECT_NE(withOption([](auto& o) { o.maxTcpSpeed = NAN; }).find("maxTcpSpeed"), std::string::npos);
  EXPECT_NE(withOption([](auto& o) { o.riseTime = 0.0; }).find("riseTime"), std::string::npos);
  EXPECT_NE(withOption([](auto& o) { o.maxTcpAcceleration = -1.0; }).find("maxTcpAcceleration"), std::string::npos);
  EXPECT_NE(withOption([](auto& o) { o.checkTimeStep = 0.0; }).find("checkTimeStep"), std::string::npos);
  EXPECT_NE(withOption([](auto& o) { o.maxTcpStep = 0.0; }).find("maxTcpStep"), std::string::npos);
}

TEST(TimeScaling, RejectsBadPaths) {
  JointPath path = linePath();
  path[10][2] = NAN;
  EXPECT_NE(scalingError(path, {}).find("waypoint 10"), std::string::npos);
  path = linePath();
  path[20][2] = 3.5;  // elbow beyond pi
  const std::string message = scalingError(path, {});
  EXPECT_NE(message.find("waypoint 20"), std::string::npos) << message;
  EXPECT_NE(message.find("elbow_joint"), std::string::npos) << message;
  EXPECT_NE(scalingError({linePath().front()}, {}).find("at least 2 waypoints"), std::string::npos);
}

}  // namespace
}  // namespace arcplan::trajectory
