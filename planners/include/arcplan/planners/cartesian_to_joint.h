#pragma once
// A TCP path to joint waypoints with the analytic UR inverse kinematics, staying on the IK branch of
// the start configuration: at every sample that branch's solution (UrInverseKinematics::solveBranch)
// in the 2·pi representation nearest to the previous waypoint, steps of any joint bounded (a
// too-large step is bisected along the path; if that does not help, the path crosses a singularity
// or changes branch and the conversion fails with the reason).
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "arcplan/planners/tcp_path.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::planners {

struct JointConversionOptions {
  double resolution = 0.01;    // m, largest TCP arc length between samples of the path
  double maxJointStep = 0.05;  // rad, largest change of any joint between consecutive waypoints
  int maxBisections = 6;       // a step above maxJointStep is halved along the path at most this often
};

enum class ConversionStatus {
  Success,
  Unreachable,   // no IK solution at some pose (outside the workspace)
  JointLimits,   // IK solutions exist, none inside the joint limits
  JointJump,     // a joint step stays above the bound after bisection: singularity or branch flip
  BranchChange,  // the path leaves the start's IK branch, or arrives on another branch than the goal's
  GoalMismatch,  // right branch, but the goal state is another 2·pi representation of the goal pose
  Rejected,      // the caller's waypoint check refused a waypoint (e.g. a collision)
};
const char* toString(ConversionStatus status);

// What a conversion produced: the waypoints up to where it stopped, and why it stopped there.
struct JointConversionResult {
  ConversionStatus status = ConversionStatus::Success;
  std::string reason;  // for users, empty on success
  double failedAtArcLength = std::numeric_limits<double>::quiet_NaN();
  std::vector<robot::Vector6> joints;
  std::vector<double> arcLengths;  // TCP arc length of each waypoint along the path
  // Status Rejected: the waypoint the check refused (the motion to it starts at joints.back()).
  std::optional<robot::Vector6> refused;

  bool ok() const { return status == ConversionStatus::Success; }
};

// "IK branch 1 (shoulder 1, sin q5 >= 0, sin q3 >= 0) and branch 5 (...) differ in the elbow (sin q3
// changes sign only through the stretched-arm singularity q3 = 0)": which of the branch bits of
// UrInverseKinematics::branchOf differ, and the singularity a continuous path would have to pass.
std::string describeBranchChange(int from, int to);

// Called for each new waypoint (not the seed) as soon as it is computed, with the previous waypoint;
// returning false stops the conversion with status Rejected (that waypoint is not appended).
using WaypointCheck =
    std::function<bool(const robot::Vector6& previous, const robot::Vector6& joints, double arcLength)>;

// Joints for the part [fromArcLength, toArcLength] of the path. `seed` is the configuration at
// fromArcLength and becomes the first waypoint unchanged. When `goal` is given the last waypoint must
// be the goal within 1e-6 rad per joint and is then replaced by it exactly (before `check` sees it).
// Throws arcplan::Error for invalid options.
JointConversionResult convertToJoints(const robot::UrInverseKinematics& ik, const TcpPath& path,
                                      const robot::Vector6& seed, const std::optional<robot::Vector6>& goal,
                                      const JointConversionOptions& options, double fromArcLength = 0.0,
                                      double toArcLength = std::numeric_limits<double>::infinity(),
                                      const WaypointCheck& check = {});

// What convertToJoints(..., check) returns, from `converted`, the same conversion without a check: the IK is not
// solved again, `check` is asked for each of its waypoints in turn. A conversion computes the same waypoints whatever
// its check says up to the one the check refuses (IK, bisection and goal depend on the path alone), so the result is
// that call's: its waypoints, status, reason and refused waypoint (a walk after its screen, planners/src). Throws
// arcplan::Error for a result without its seed or with arc lengths that do not match its waypoints.
JointConversionResult checkConverted(const JointConversionResult& converted, const TcpPath& path,
                                     const WaypointCheck& check);

}  // namespace arcplan::planners
