#include "arcplan/planners/cartesian_to_joint.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arcplan/common/error.h"

namespace arcplan::planners {
namespace {

constexpr double kGoalTolerance = 1e-6;  // rad per joint

class Converter {
public:
  Converter(const robot::UrInverseKinematics& ik, const ArcPath& path, const JointConversionOptions& options,
            JointWaypoints& result, int branch)
      : ik_(ik), path_(path), options_(options), result_(result), branch_(branch) {}

  // Appends the waypoint at `arcLength` (and bisection points before it); false on failure.
  bool advance(double arcLength, const Eigen::Isometry3d& pose, int depth) {
    const robot::Vector6& previous = result_.joints.back();
    const double previousArcLength = result_.arcLengths.back();
    const std::optional<robot::Vector6> q = ik_.solveNearest(pose, previous);
    if (!q) {
      const bool reachable = !ik_.solveBranches(pose).empty();
      return fail(reachable ? ConversionStatus::JointLimits : ConversionStatus::Unreachable, arcLength,
                  reachable ? "every IK solution is outside the joint limits" : "the TCP pose is out of reach (no IK solution)");
    }
    int joint = 0;
    const double step = (*q - previous).cwiseAbs().maxCoeff(&joint);
    if (step > options_.maxJointStep) {
      if (depth < options_.maxBisections) {
        const double middle = 0.5 * (previousArcLength + arcLength);
        return advance(middle, path_.pose(middle), depth + 1) && advance(arcLength, pose, depth + 1);
      }
      std::ostringstream message;
      message << "joint " << joint << " would jump " << step << " rad within " << arcLength - previousArcLength
              << " m of TCP motion (bound " << options_.maxJointStep
              << " rad): the path passes a singularity or flips IK branch";
      return fail(ConversionStatus::JointJump, arcLength, message.str());
    }
    if (ik_.branchOf(*q) != branch_) {
      std::ostringstream message;
      message << "the path leaves the start configuration's IK branch " << branch_ << " (now " << ik_.branchOf(*q) << ")";
      return fail(ConversionStatus::BranchChange, arcLength, message.str());
    }
    result_.joints.push_back(*q);
    result_.arcLengths.push_back(arcLength);
    return true;
  }

  bool fail(ConversionStatus status, double arcLength, const std::string& what) {
    std::ostringstream message;
    message << what << " at TCP arc length " << arcLength << " m of " << path_.length() << " m";
    result_.status = status;
    result_.reason = message.str();
    result_.failedAtArcLength = arcLength;
    return false;
  }

private:
  const robot::UrInverseKinematics& ik_;
  const ArcPath& path_;
  const JointConversionOptions& options_;
  JointWaypoints& result_;
  int branch_;
};

}  // namespace

const char* toString(ConversionStatus status) {
  switch (status) {
    case ConversionStatus::Success: return "success";
    case ConversionStatus::Unreachable: return "unreachable";
    case ConversionStatus::JointLimits: return "joint limits";
    case ConversionStatus::JointJump: return "joint jump";
    case ConversionStatus::BranchChange: return "branch change";
    case ConversionStatus::GoalMismatch: return "goal mismatch";
  }
  return "unknown";
}

JointWaypoints convertToJoints(const robot::UrInverseKinematics& ik, const ArcPath& path, const robot::Vector6& seed,
                               const std::optional<robot::Vector6>& goal, const JointConversionOptions& options,
                               double fromArcLength, double toArcLength) {
  if (!(options.maxJointStep > 0.0) || !std::isfinite(options.maxJointStep)) {
    throw Error("joint conversion: max joint step must be a finite number > 0 rad");
  }
  if (options.maxBisections < 0) throw Error("joint conversion: max bisections must be >= 0");
  JointWaypoints result;
  result.joints.push_back(seed);
  result.arcLengths.push_back(std::max(fromArcLength, 0.0));
  Converter converter(ik, path, options, result, ik.branchOf(seed));
  constexpr double kEpsilon = 1e-12;
  for (const PathSample& sample : path.sample(options.resolution)) {
    if (sample.arcLength <= fromArcLength + kEpsilon) continue;
    if (sample.arcLength > toArcLength + kEpsilon) break;
    if (!converter.advance(sample.arcLength, sample.pose, 0)) return result;
  }
  if (goal) {
    const robot::Vector6& arrival = result.joints.back();
    const int arrivalBranch = ik.branchOf(arrival), goalBranch = ik.branchOf(*goal);
    if (arrivalBranch != goalBranch) {
      std::ostringstream message;
      message << "the path stays on IK branch " << arrivalBranch << " of the start, but the goal configuration is on branch "
              << goalBranch << " (a TCP path cannot change branch; give a goal on the start's branch)";
      converter.fail(ConversionStatus::BranchChange, result.arcLengths.back(), message.str());
      return result;
    }
    const double difference = (arrival - *goal).cwiseAbs().maxCoeff();
    if (difference > kGoalTolerance) {
      std::ostringstream message;
      message << "the path reaches the goal pose with joints " << difference
              << " rad away from the goal configuration (another 2*pi representation of the same pose)";
      converter.fail(ConversionStatus::GoalMismatch, result.arcLengths.back(), message.str());
      return result;
    }
    result.joints.back() = *goal;
  }
  return result;
}

}  // namespace arcplan::planners
