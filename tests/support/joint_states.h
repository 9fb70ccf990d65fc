#pragma once
// Joint vectors against a robot's joint limits in tests: seeded random draws inside them
// (random_joint_state.h), the check that a vector is inside them, and the angle between two vectors
// whose joints may differ by whole turns.
#include <algorithm>
#include <cmath>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "arcplan/robot/robot_model.h"
#include "support/random_joint_state.h"

namespace arcplan::testing {

// A test failure for every joint of q below its lower or above its upper limit.
inline void expectWithinJointLimits(const robot::RobotModel& robot, const Eigen::VectorXd& q) {
  ASSERT_EQ(q.size(), robot.dof());
  for (int j = 0; j < robot.dof(); ++j) {
    const auto& limits = robot.joints()[j].limits;
    EXPECT_GE(q[j], limits.lower) << "joint " << j << " (" << robot.joints()[j].name << ")";
    EXPECT_LE(q[j], limits.upper) << "joint " << j << " (" << robot.joints()[j].name << ")";
  }
}

// The largest joint difference of a and b with whole turns taken out (in [0, π]): IK returns a joint
// with ±2π limits in either of its two representations.
inline double angularDistanceModuloTwoPi(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double worst = 0.0;
  for (Eigen::Index j = 0; j < a.size(); ++j) worst = std::max(worst, std::abs(std::remainder(a[j] - b[j], 2 * M_PI)));
  return worst;
}

}  // namespace arcplan::testing
