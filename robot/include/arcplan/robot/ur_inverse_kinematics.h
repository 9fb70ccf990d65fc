#pragma once
// Closed-form inverse kinematics of UR-type arms (three parallel middle axes, non-spherical wrist),
// after Hawkins' analysis of the UR5/UR10: up to 8 branches per tip pose.
//
// The DH numbers are read off the model's geometry at q = 0 and verified against the chain's own
// forward kinematics, so the same code serves arcplan's UR10e, the official UR description, or a
// UR chain with a longer tool frame as tip.
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/robot_model.h"

namespace arcplan::robot {

using Vector6 = Eigen::Matrix<double, 6, 1>;

// Standard DH of a UR arm: alpha = (pi/2, 0, 0, pi/2, -pi/2, 0), a1 = a4 = a5 = a6 = 0.
struct UrDhParameters {
  double d1 = 0.0, a2 = 0.0, a3 = 0.0, d4 = 0.0, d5 = 0.0, d6 = 0.0;
};

// Pose of DH frame 6 in DH frame 0 for joint angles q.
Eigen::Isometry3d urDhForwardKinematics(const UrDhParameters& dh, const Vector6& q);

class UrInverseKinematics {
public:
  // Throws arcplan::Error when the chain is not a 6-joint UR-type arm.
  explicit UrInverseKinematics(const RobotModel& model);

  const UrDhParameters& dhParameters() const { return dh_; }
  // DH frame 0 in the model's base frame, and the tip frame in DH frame 6.
  const Eigen::Isometry3d& baseToDh0() const { return baseToDh0_; }
  const Eigen::Isometry3d& dh6ToTip() const { return dh6ToTip_; }

  // The analytic branches for a tip pose in the model's base frame, each angle in (-pi, pi],
  // ignoring joint limits. At the wrist singularity (q5 = 0 or pi) only q4 + q6 (or q4 - q6) is
  // determined; q6 is then set to `q6AtWristSingularity`.
  std::vector<Vector6> solveBranches(const Eigen::Isometry3d& tipPose, double q6AtWristSingularity = 0.0) const;

  // One branch (numbered as branchOf) of the same closed form, angles in (-pi, pi]; nullopt when
  // that branch cannot reach the pose. Eight times cheaper than solveBranches: what a path tracker
  // that must stay on its start's branch needs.
  std::optional<Vector6> solveBranch(const Eigen::Isometry3d& tipPose, int branch,
                                     double q6AtWristSingularity = 0.0) const;

  // Every solution inside the joint limits: each branch in all of its 2·pi representations.
  std::vector<Vector6> solveAll(const Eigen::Isometry3d& tipPose) const;

  // The in-limit solution closest to `seed` (Euclidean joint distance), or nullopt when the pose
  // is out of reach or no branch fits the limits.
  std::optional<Vector6> solveNearest(const Eigen::Isometry3d& tipPose, const Vector6& seed) const;

  // Branch of configuration q, 0..7: bit 0 shoulder (q1 choice), bit 1 wrist (sign of sin q5),
  // bit 2 elbow (sign of sin q3). Configurations on one continuous IK path share it unless the
  // path crosses a singularity.
  int branchOf(const Vector6& q) const;

  // The in-limit representation of `q` (each joint shifted by a multiple of 2·pi) nearest to
  // `reference`; nullopt if some joint has none.
  std::optional<Vector6> nearestRepresentation(const Vector6& q, const Vector6& reference) const;

private:
  struct TargetFrame;
  struct ShoulderStep;
  struct WristStep;
  TargetFrame targetFrame(const Eigen::Isometry3d& tipPose) const;
  std::optional<ShoulderStep> shoulderStep(const TargetFrame& target, int shoulder) const;
  WristStep wristStep(const TargetFrame& target, const ShoulderStep& shoulder, int wrist,
                      double q6AtWristSingularity) const;
  std::optional<Vector6> elbowStep(const TargetFrame& target, const ShoulderStep& shoulder, const WristStep& wrist,
                                   int elbow) const;

  UrDhParameters dh_;
  Eigen::Isometry3d baseToDh0_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d dh6ToTip_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d dh0ToBase_ = Eigen::Isometry3d::Identity();  // inverses, kept for solveBranches
  Eigen::Isometry3d tipToDh6_ = Eigen::Isometry3d::Identity();
  Vector6 lower_, upper_;
};

}  // namespace arcplan::robot
