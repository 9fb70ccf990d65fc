#pragma once
// IK round trips of the UR tests (robot_tests and robot_shared_data_tests): seeded random
// configurations -> tip pose by forward kinematics -> every analytic IK branch.
#include <algorithm>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/ur_inverse_kinematics.h"
#include "support/joint_states.h"

namespace arcplan::testing {

// A test failure unless q's tip pose is `target` to 1e-9 (m for the position, rad for the rotation).
inline void expectReproducesPose(const robot::RobotModel& model, const robot::Vector6& q,
                                 const Eigen::Isometry3d& target) {
  const Eigen::Isometry3d pose = robot::tipPose(model, q);
  EXPECT_LE((pose.translation() - target.translation()).norm(), 1e-9) << model.name() << " " << q.transpose();
  EXPECT_LE(robot::rotationDistance(pose.linear(), target.linear()), 1e-9) << model.name() << " " << q.transpose();
}

// `trials` configurations drawn inside the limits with `seed`, each solved from its tip pose: every
// solution must reproduce the pose (expectReproducesPose). Returns how many configurations are among
// their own solutions to `tolerance` (largest joint difference, whole turns aside).
inline int urRoundTrips(const robot::RobotModel& model, unsigned seed, int trials, double tolerance) {
  const robot::UrInverseKinematics ik(model);
  std::mt19937 random(seed);
  int found = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const robot::Vector6 q = randomJointState(model, random);
    const Eigen::Isometry3d target = robot::tipPose(model, q);
    double closest = 1e9;
    for (const robot::Vector6& s : ik.solveBranches(target)) {
      expectReproducesPose(model, s, target);
      closest = std::min(closest, angularDistanceModuloTwoPi(s, q));
    }
    if (closest < tolerance) ++found;
  }
  return found;
}

}  // namespace arcplan::testing
