#include "arcplan/robot/pose.h"

#include <algorithm>
#include <cmath>

namespace arcplan::robot {

Eigen::Matrix3d rotationFromRpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& r) {
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  if (std::abs(r(2, 0)) > 1.0 - 1e-12) {
    // Gimbal lock: only yaw - roll (or yaw + roll) is defined; put it all in yaw.
    return {0.0, pitch, std::atan2(-r(0, 1), r(1, 1))};
  }
  return {std::atan2(r(2, 1), r(2, 2)), pitch, std::atan2(r(1, 0), r(0, 0))};
}

Eigen::Isometry3d poseFromXyzRpy(const std::array<double, 6>& v) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() << v[0], v[1], v[2];
  pose.linear() = rotationFromRpy(v[3], v[4], v[5]);
  return pose;
}

std::array<double, 6> xyzRpyFromPose(const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d rpy = rpyFromRotation(pose.linear());
  const Eigen::Vector3d& p = pose.translation();
  return {p.x(), p.y(), p.z(), rpy.x(), rpy.y(), rpy.z()};
}

double rotationDistance(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  // The angle-axis of a^T b; via the quaternion for accuracy near 0 and pi.
  const Eigen::Quaterniond relative(a.transpose() * b);
  const double vectorNorm = relative.vec().norm();
  return 2.0 * std::atan2(vectorNorm, std::abs(relative.w()));
}

}  // namespace arcplan::robot
