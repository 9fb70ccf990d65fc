#pragma once
// Closed-form inverse kinematics of UR-type arms (three parallel middle axes, non-spherical wrist),
// after Hawkins' analysis of the UR5/UR10: up to 8 branches per tip pose.
//
// The DH numbers are read off the model's geometry at q = 0 (any UR type, CB-series or e-series,
// URDF frames of ROS 1 or ROS 2 style, the arm standing anywhere in the base frame, any tool frame
// as tip) and the chain's own forward kinematics is compared with that ideal chain. A URDF's chain
// may differ from it by the rounding of its numbers (kUrdfChainTolerance); a chain built from a
// robot's calibration file (RobotModel::calibrated) by calibration offsets
// (kCalibratedChainTolerance). Where the difference is not negligible, every analytic solution is
// refined by Newton steps on the true chain, so solutions reproduce the pose to 1e-11.
#include <memory>
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

// Largest tip position (m) and rotation (rad) difference between a URDF's chain and the ideal UR
// chain: official files write pi/2 as 1.570796327 or 1.570796325 and carry 1e-11 m offsets (1e-8
// at the tip); a real deviation of another arm is millimetres.
inline constexpr double kUrdfChainTolerance = 1e-6;
// The same for a chain from a calibration file: factory calibrations move joint frames by
// millimetres and milliradians.
inline constexpr double kCalibratedChainTolerance = 0.02;

namespace detail {
struct JointChain;
}

class UrInverseKinematics {
public:
  // Throws arcplan::Error when the chain is not a 6-joint UR-type arm, saying by how much it differs
  // from the ideal UR chain and what the tolerance is.
  explicit UrInverseKinematics(const RobotModel& model);

  const UrDhParameters& dhParameters() const { return dh_; }
  // How far the model's chain is from the ideal UR chain of dhParameters (m, rad).
  double translationDeviation() const { return translationDeviation_; }
  double rotationDeviation() const { return rotationDeviation_; }

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
  // `inside` > 0 keeps the angles where two branches merge that far inside the branch (Newton seeds).
  std::optional<ShoulderStep> shoulderStep(const TargetFrame& target, int shoulder, double inside) const;
  WristStep wristStep(const TargetFrame& target, const ShoulderStep& shoulder, int wrist, double q6AtWristSingularity,
                      double inside) const;
  std::optional<Vector6> elbowStep(const TargetFrame& target, const ShoulderStep& shoulder, const WristStep& wrist,
                                   int elbow, double inside) const;
  std::optional<Vector6> analyticBranch(const TargetFrame& target, int branch, double q6AtWristSingularity,
                                        double inside) const;
  // An angle in [0, pi] at which two branches merge, kept `inside` away from 0 and pi.
  static double awayFromMergedBranches(double angle, double inside);
  // The analytic solution q of the ideal chain made exact on the true chain; false if it cannot be.
  bool refine(const Eigen::Isometry3d& tipPose, Vector6& q) const;

  UrDhParameters dh_;
  Eigen::Isometry3d dh0ToBase_ = Eigen::Isometry3d::Identity();  // base frame -> DH frame 0
  Eigen::Isometry3d tipToDh6_ = Eigen::Isometry3d::Identity();
  double translationDeviation_ = 0.0, rotationDeviation_ = 0.0;
  // The true chain, kept when the ideal one differs from it by more than rounding noise.
  std::shared_ptr<const detail::JointChain> refinedChain_;
  double reachSlack_ = 1e-9;  // how far beyond 1 |cos q3| may be and still count as reachable
  Vector6 lower_, upper_;
};

}  // namespace arcplan::robot
