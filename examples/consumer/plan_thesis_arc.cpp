// Uses an installed arcplan: the built-in UR10e, forward and inverse kinematics of thesis pose A.
#include <cmath>
#include <iostream>

#include <arcplan/robot/kinematics.h>
#include <arcplan/robot/pose.h>
#include <arcplan/robot/ur_inverse_kinematics.h>

int main() {
  const auto& robot = arcplan::robot::ur10e();
  const arcplan::robot::UrInverseKinematics ik(robot);
  const auto poseA = arcplan::robot::poseFromXyzRpy({0.4, -0.4, 0.25, 0.0, -M_PI, M_PI / 2});
  arcplan::robot::Vector6 seed;
  seed << -1.1, -1.5, 2.35, -2.4, -1.57, -1.1;
  const auto q = ik.solveNearest(poseA, seed);
  if (!q) {
    std::cerr << "pose A unreachable\n";
    return 1;
  }
  const auto reached = arcplan::robot::tipPose(robot, *q);
  std::cout << "joints " << q->transpose() << "\n";
  std::cout << "tool0 " << reached.translation().transpose() << "\n";
  return (reached.translation() - poseA.translation()).norm() < 1e-9 ? 0 : 1;
}
