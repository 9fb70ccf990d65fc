// The metrics of docs/metrics.md on a hand-made trajectory whose values are worked out in the comments.
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "arcplan/trajectory/metrics.h"

namespace arcplan::trajectory {
namespace {

robot::Vector6 uniform(double value) { return robot::Vector6::Constant(value); }

TimedTrajectory handMadeTrajectory() {
  TimedTrajectory trajectory;
  trajectory.densePath = {uniform(0.0), uniform(0.1), uniform(0.3)};
  trajectory.tcpPathLength = 0.9;
  trajectory.knots = {uniform(0.0), uniform(0.3)};
  trajectory.knotTimes = {0.0, 4.0};
  trajectory.time = {0.0, 1.0, 2.0, 3.0, 4.0};
  trajectory.tcpSpeed = {0.0, 0.2, 0.3, 0.2, 0.0};
  trajectory.tcpSpeedLimit = 0.25;
  trajectory.jointSpeedLimits << 2.0, 2.0, 3.0, 3.0, 3.0, 3.0;
  trajectory.velocity.assign(5, robot::Vector6::Zero());
  trajectory.velocity[1][2] = -1.5;  // 0.5 of its limit
  trajectory.velocity[3][0] = 1.9;   // 0.95 of its limit
  trajectory.position.assign(5, robot::Vector6::Zero());
  trajectory.acceleration.assign(5, robot::Vector6::Zero());
  trajectory.tcpPosition.assign(5, Eigen::Vector3d::Zero());
  return trajectory;
}

TEST(TrajectoryMetrics, HandComputedValues) {
  // Planner path: two steps of 0.3 and 0.4 on joint 0 only.
  robot::Vector6 a = uniform(0.0), b = a, c = a;
  b[0] = 0.3;
  c[0] = -0.1;
  const TrajectoryMetrics metrics = computeMetrics({a, b, c}, handMadeTrajectory());
  EXPECT_DOUBLE_EQ(metrics.tcpPathLength, 0.9);
  EXPECT_NEAR(metrics.jointPathLength, 0.7, 1e-15);
  EXPECT_DOUBLE_EQ(metrics.executionTime, 4.0);
  EXPECT_DOUBLE_EQ(metrics.meanTcpSpeed, 0.225);
  EXPECT_DOUBLE_EQ(metrics.peakTcpSpeed, 0.3);
  // Linear between samples the speed crosses 0.25 at t = 1.5 and t = 2.5: 1 s above.
  EXPECT_NEAR(metrics.timeAboveLimit, 1.0, 1e-12);
  EXPECT_NEAR(metrics.maxJointSpeedRatio, 0.95, 1e-15);
  EXPECT_TRUE(std::isnan(metrics.minClearance));
}

TEST(TrajectoryMetrics, ClearanceIsTheMinimumOverTheDensePath) {
  std::size_t calls = 0;
  const TrajectoryMetrics metrics =
      computeMetrics({uniform(0.0), uniform(0.3)}, handMadeTrajectory(), [&](const robot::Vector6& q, double) {
        ++calls;
        return 0.5 - q[0];
      });
  EXPECT_EQ(calls, 3u);
  EXPECT_DOUBLE_EQ(metrics.minClearance, 0.2);
}

// Each waypoint is asked with the smallest clearance found before it; a function answering `enough` (or more)
// wherever the true value is not below it still gives the exact minimum, wherever along the path it lies.
TEST(TrajectoryMetrics, ClearanceIsExactWhereTheFunctionBoundsTheWaypointsAboveTheMinimumSoFar) {
  JointPath dense;
  for (int k = 0; k <= 40; ++k) dense.push_back(uniform(0.01 * k));
  const auto truth = [](const robot::Vector6& q) { return 0.3 + std::cos(9.0 * q[0]) * 0.1 + q[0] * q[0]; };
  double exact = INFINITY;
  for (const robot::Vector6& q : dense) exact = std::min(exact, truth(q));
  std::vector<double> asked;
  const double bounded = minClearanceAlong(dense, [&](const robot::Vector6& q, double enough) {
    asked.push_back(enough);
    const double value = truth(q);
    return value >= enough ? enough + 1.0 : value;  // any value >= enough
  });
  EXPECT_EQ(bounded, exact);
  ASSERT_EQ(asked.size(), dense.size());  // each waypoint once
  EXPECT_EQ(asked.front(), INFINITY);
  for (std::size_t k = 1; k < asked.size(); ++k) EXPECT_LE(asked[k], asked[k - 1]);  // the running minimum
}

TEST(TrajectoryMetrics, NoTimeAboveWhenUnderTheLimit) {
  TimedTrajectory trajectory = handMadeTrajectory();
  trajectory.tcpSpeedLimit = 0.3;  // touching the limit is not above it
  EXPECT_EQ(computeMetrics({uniform(0.0), uniform(0.3)}, trajectory).timeAboveLimit, 0.0);
}

TEST(TrajectoryMetrics, JsonHasExactlyTheDesignKeys) {
  const TrajectoryMetrics metrics = computeMetrics({uniform(0.0), uniform(0.3)}, handMadeTrajectory());
  const nlohmann::json json = toJson(metrics);
  std::set<std::string> keys;
  for (const auto& item : json.items()) keys.insert(item.key());
  const std::set<std::string> expected{"tcp_path_length_m",  "joint_path_length_rad", "execution_time_s",
                                       "mean_tcp_speed_mps", "peak_tcp_speed_mps",    "time_above_limit_s",
                                       "min_clearance_m",    "max_joint_speed_ratio"};
  EXPECT_EQ(keys, expected);
  EXPECT_TRUE(json["min_clearance_m"].is_null());
  EXPECT_DOUBLE_EQ(json["execution_time_s"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(json["peak_tcp_speed_mps"].get<double>(), 0.3);

  TrajectoryMetrics withClearance = metrics;
  withClearance.minClearance = 0.04;
  EXPECT_DOUBLE_EQ(toJson(withClearance)["min_clearance_m"].get<double>(), 0.04);
}

}  // namespace
}  // namespace arcplan::trajectory
