#pragma once
// Joint vectors against a robot's joint limits in tests: seeded random draws inside them, and the
// check that a vector is inside them.
#include <random>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "arcplan/robot/robot_model.h"

namespace arcplan::testing {

// One uniform draw per joint, in joint order, between its lower and upper limit. `Random` is a
// standard engine (std::mt19937, std::mt19937_64) the caller seeded, so a test's states repeat.
template <typename Random>
Eigen::VectorXd randomJointState(const robot::RobotModel& robot, Random& random) {
  Eigen::VectorXd q(robot.dof());
  for (int j = 0; j < robot.dof(); ++j) {
    const auto& limits = robot.joints()[j].limits;
    q[j] = std::uniform_real_distribution<double>(limits.lower, limits.upper)(random);
  }
  return q;
}

// A test failure for every joint of q below its lower or above its upper limit.
inline void expectWithinJointLimits(const robot::RobotModel& robot, const Eigen::VectorXd& q) {
  ASSERT_EQ(q.size(), robot.dof());
  for (int j = 0; j < robot.dof(); ++j) {
    const auto& limits = robot.joints()[j].limits;
    EXPECT_GE(q[j], limits.lower) << "joint " << j << " (" << robot.joints()[j].name << ")";
    EXPECT_LE(q[j], limits.upper) << "joint " << j << " (" << robot.joints()[j].name << ")";
  }
}

}  // namespace arcplan::testing
