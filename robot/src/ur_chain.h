#pragma once
// The six-joint chain of a RobotModel reduced to what UR inverse kinematics needs, and the ideal UR
// (DH) chain fitted to it. Internal to arcplan::robot (ur_inverse_kinematics.cpp uses it).
#include <array>
#include <string>

#include <Eigen/Geometry>

#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::robot::detail {

// Joint j turns about axis[j] (unit, in its own frame) after the fixed transform origin[j] from the
// previous joint's frame (the base for j = 0); tip is the tip link in the last joint's frame. The
// same numbers as the model's links with the fixed links between joints multiplied out, so forward
// kinematics of the tip needs no workspace and six products.
struct JointChain {
  std::array<Eigen::Isometry3d, 6> origin;
  std::array<Eigen::Vector3d, 6> axis;
  Eigen::Isometry3d tip = Eigen::Isometry3d::Identity();
};

// Throws arcplan::Error when the model's tip is not moved by exactly six joints.
JointChain jointChainOf(const RobotModel& model);

// Tip pose in the base frame; with `jointFrames`, also each joint's frame (after its rotation).
Eigen::Isometry3d chainTipPose(const JointChain& chain, const Vector6& q,
                               std::array<Eigen::Isometry3d, 6>* jointFrames = nullptr);

// The ideal UR chain closest to `chain` at q = 0, and how far the two are apart elsewhere.
struct UrChainFit {
  UrDhParameters dh;
  Eigen::Isometry3d baseToDh0 = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d dh6ToTip = Eigen::Isometry3d::Identity();
  double translationDeviation = 0.0;  // m, largest tip position difference at the test configurations
  double rotationDeviation = 0.0;     // rad, largest tip rotation difference
};

// Throws arcplan::Error naming `robotName` when the geometry has no UR shape at all (elbow axis on
// the shoulder axis, every tool frame on the wrist-2 axis). Whether the deviation is acceptable is
// for the caller to decide.
UrChainFit fitUrChain(const JointChain& chain, const std::string& robotName);

// Newton steps on the true chain from `q` (an analytic solution of the fitted ideal chain) until the
// tip reaches `target`; false when it does not converge below 1e-11 m and rad.
bool refineOnChain(const JointChain& chain, const Eigen::Isometry3d& target, Vector6& q);

}  // namespace arcplan::robot::detail
