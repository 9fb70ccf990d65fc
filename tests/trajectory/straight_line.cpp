#include "straight_line.h"

#include <cmath>
#include <stdexcept>

#include "arcplan/robot/pose.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::trajectory::testing {

Eigen::Isometry3d thesisPoseA() { return robot::poseFromXyzRpy({0.4, -0.4, 0.25, 0.0, -M_PI, M_PI / 2}); }
Eigen::Isometry3d thesisPoseB() { return robot::poseFromXyzRpy({0.5, 0.4, 0.46, 0.0, -M_PI, M_PI / 2}); }

robot::Vector6 thesisSeedA() {
  robot::Vector6 seed;
  seed << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098;
  return seed;
}

JointPath straightLinePath(const robot::RobotModel& model, int segments) {
  const robot::UrInverseKinematics ik(model);
  const Eigen::Isometry3d a = thesisPoseA(), b = thesisPoseB();
  JointPath path;
  robot::Vector6 seed = thesisSeedA();
  for (int i = 0; i <= segments; ++i) {
    Eigen::Isometry3d pose = a;
    pose.translation() = a.translation() + (b.translation() - a.translation()) * (double(i) / segments);
    const auto q = ik.solveNearest(pose, seed);
    if (!q) throw std::runtime_error("no IK solution on the thesis line");
    path.push_back(*q);
    seed = *q;
  }
  return path;
}

}  // namespace arcplan::trajectory::testing
