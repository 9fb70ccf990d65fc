#pragma once
// Seeded random joint vectors inside a robot's joint limits, for tests and the micro-benchmarks
// (perf/), which draw their sample states the same way. No GoogleTest here: perf includes it too.
#include <random>

#include <Eigen/Core>

#include "arcplan/robot/robot_model.h"

namespace arcplan::testing {

// One uniform draw per joint, in joint order, between its lower and upper limit. `Random` is a
// standard engine (std::mt19937, std::mt19937_64) the caller seeded, so the states repeat.
template <typename Random>
Eigen::VectorXd randomJointState(const robot::RobotModel& robot, Random& random) {
  Eigen::VectorXd q(robot.dof());
  for (int j = 0; j < robot.dof(); ++j) {
    const auto& limits = robot.joints()[j].limits;
    q[j] = std::uniform_real_distribution<double>(limits.lower, limits.upper)(random);
  }
  return q;
}

}  // namespace arcplan::testing
