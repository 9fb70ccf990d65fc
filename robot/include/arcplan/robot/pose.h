#pragma once
// Poses as the command line and scene files write them: [x, y, z, roll, pitch, yaw] with URDF
// fixed-axis RPY, R = Rz(yaw)·Ry(pitch)·Rx(roll). Rotations are compared as rotations (angle of
// the relative rotation), never as RPY triples.
#include <array>

#include <Eigen/Geometry>

namespace arcplan::robot {

Eigen::Matrix3d rotationFromRpy(double roll, double pitch, double yaw);
// One RPY triple of R (pitch in [-pi/2, pi/2]); several triples describe the same rotation.
Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& rotation);

Eigen::Isometry3d poseFromXyzRpy(const std::array<double, 6>& xyzRpy);
std::array<double, 6> xyzRpyFromPose(const Eigen::Isometry3d& pose);

// Angle (rad, in [0, pi]) of the rotation taking a to b.
double rotationDistance(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

}  // namespace arcplan::robot
