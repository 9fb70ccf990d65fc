#include "arcplan/planners/cartesian_to_joint.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arcplan/common/error.h"

namespace arcplan::planners {
namespace {

constexpr double kGoalTolerance = 1e-6;  // rad per joint

// A conversion's reason: what stopped it, and where.
std::string stoppedAt(const std::string& what, double arcLength, double pathLength) {
  std::ostringstream message;
  message << what << " at TCP arc length " << arcLength << " m of " << pathLength << " m";
  return message.str();
}

constexpr const char* kRejected = "the waypoint check rejected the waypoint";

class Converter {
public:
  Converter(const robot::UrInverseKinematics& ik, const TcpPath& path, const JointConversionOptions& options,
            const std::optional<robot::Vector6>& goal, const WaypointCheck& check, JointConversionResult& result)
      : ik_(ik),
        path_(path),
        options_(options),
        goal_(goal),
        check_(check),
        result_(result),
        branch_(ik.branchOf(result.joints.front())) {}

  // Appends the waypoint at `arcLength` (and bisection points before it); false on failure.
  // `arrival`: this is the path's end, where the goal configuration (if any) must be met.
  bool advance(double arcLength, const Eigen::Isometry3d& pose, bool arrival, int depth = 0) {
    const robot::Vector6& previous = result_.joints.back();
    const double previousArcLength = result_.arcLengths.back();
    // Only the start's branch is solved: a TCP path cannot change branch without passing a
    // singularity, which shows up below as a joint jump.
    const auto onBranch = ik_.solveBranch(pose, branch_, previous[5]);
    const std::optional<robot::Vector6> q = onBranch ? ik_.nearestRepresentation(*onBranch, previous) : std::nullopt;
    if (!q) {
      if (onBranch)
        return fail(ConversionStatus::JointLimits, arcLength, "the IK solution is outside the joint limits");
      const bool reachable = !ik_.solveBranches(pose).empty();
      return fail(reachable ? ConversionStatus::BranchChange : ConversionStatus::Unreachable, arcLength,
                  reachable ? "the start configuration's IK branch " + std::to_string(branch_) +
                                  " cannot reach the TCP pose (other branches can)"
                            : "the TCP pose is out of reach (no IK solution)");
    }
    int joint = 0;
    const double step = (*q - previous).cwiseAbs().maxCoeff(&joint);
    if (step > options_.maxJointStep) {
      if (depth < options_.maxBisections) {
        const double middle = 0.5 * (previousArcLength + arcLength);
        return advance(middle, path_.pose(middle), false, depth + 1) && advance(arcLength, pose, arrival, depth + 1);
      }
      std::ostringstream message;
      message << "joint " << joint << " would jump " << step << " rad within " << arcLength - previousArcLength
              << " m of TCP motion (bound " << options_.maxJointStep
              << " rad): the path passes a singularity or flips IK branch";
      return fail(ConversionStatus::JointJump, arcLength, message.str());
    }
    // The goal must be this configuration (same branch and 2·pi representation).
    if (arrival && !meetsGoal(*q, arcLength)) return false;
    const robot::Vector6 accepted = arrival && goal_ ? *goal_ : *q;
    if (check_ && !check_(previous, accepted, arcLength)) {
      result_.refused = accepted;
      return fail(ConversionStatus::Rejected, arcLength, kRejected);
    }
    result_.joints.push_back(accepted);
    result_.arcLengths.push_back(arcLength);
    return true;
  }

  bool meetsGoal(const robot::Vector6& arrival, double arcLength) {
    const int arrivalBranch = ik_.branchOf(arrival);
    if (arrivalBranch != branch_) {
      std::ostringstream message;
      message << "the path leaves the start configuration's IK branch (" << describeBranchChange(branch_, arrivalBranch)
              << "): it passes a singularity";
      return fail(ConversionStatus::BranchChange, arcLength, message.str());
    }
    if (!goal_) return true;
    const int goalBranch = ik_.branchOf(*goal_);
    if (arrivalBranch != goalBranch) {
      std::ostringstream message;
      message << "the path stays on the start's IK branch, but the goal configuration is on another ("
              << describeBranchChange(arrivalBranch, goalBranch)
              << "; a TCP path cannot change branch: give a goal on the start's branch)";
      return fail(ConversionStatus::BranchChange, arcLength, message.str());
    }
    const double difference = (arrival - *goal_).cwiseAbs().maxCoeff();
    if (difference > kGoalTolerance) {
      std::ostringstream message;
      message << "the path reaches the goal pose with joints " << difference
              << " rad away from the goal configuration (another 2*pi representation of the same pose)";
      return fail(ConversionStatus::GoalMismatch, arcLength, message.str());
    }
    return true;
  }

  bool fail(ConversionStatus status, double arcLength, const std::string& what) {
    result_.status = status;
    result_.reason = stoppedAt(what, arcLength, path_.length());
    result_.failedAtArcLength = arcLength;
    return false;
  }

private:
  const robot::UrInverseKinematics& ik_;
  const TcpPath& path_;
  const JointConversionOptions& options_;
  const std::optional<robot::Vector6>& goal_;
  const WaypointCheck& check_;
  JointConversionResult& result_;
  int branch_;
};

}  // namespace

std::string describeBranchChange(int from, int to) {
  const auto describe = [](int branch) {
    std::ostringstream text;
    text << "branch " << branch << " (shoulder solution " << (branch & 1) << ", sin q5 "
         << ((branch & 2) != 0 ? "< 0" : ">= 0") << ", sin q3 " << ((branch & 4) != 0 ? "< 0" : ">= 0") << ")";
    return text.str();
  };
  // The bits of UrInverseKinematics::branchOf and the singularity between their two values.
  struct Bit {
    int mask;
    const char* part;
    const char* singularity;
  };
  static const Bit bits[] = {{1, "shoulder", "the wrist centre crossing the base axis"},
                             {2, "wrist", "q5 = 0, wrist axes 4 and 6 aligned"},
                             {4, "elbow", "q3 = 0, the arm stretched"}};
  std::ostringstream text;
  text << "IK " << describe(from) << " and " << describe(to) << " differ in";
  bool first = true;
  for (const Bit& bit : bits) {
    if (((from ^ to) & bit.mask) == 0) continue;
    text << (first ? " the " : "; the ") << bit.part << " (only through the singularity " << bit.singularity << ")";
    first = false;
  }
  return text.str();
}

const char* toString(ConversionStatus status) {
  // In the order of the enumerators.
  static const char* const names[] = {"success",       "unreachable",   "joint limits", "joint jump",
                                      "branch change", "goal mismatch", "rejected"};
  return names[static_cast<int>(status)];
}

JointConversionResult convertToJoints(const robot::UrInverseKinematics& ik, const TcpPath& path,
                                      const robot::Vector6& seed, const std::optional<robot::Vector6>& goal,
                                      const JointConversionOptions& options, double fromArcLength, double toArcLength,
                                      const WaypointCheck& check) {
  if (!(options.maxJointStep > 0.0) || !std::isfinite(options.maxJointStep)) {
    throw Error("joint conversion: max joint step must be a finite number > 0 rad");
  }
  if (options.maxBisections < 0) throw Error("joint conversion: max bisections must be >= 0");
  JointConversionResult result;
  result.joints.push_back(seed);
  result.arcLengths.push_back(std::max(fromArcLength, 0.0));
  constexpr double kEpsilon = 1e-12;
  const double end = std::min(toArcLength, path.length());
  // The goal applies only when the conversion runs to the end of the path.
  const std::optional<robot::Vector6> goalHere = end >= path.length() - kEpsilon ? goal : std::nullopt;
  Converter converter(ik, path, options, goalHere, check, result);
  for (const PathSample& sample : path.sample(options.resolution)) {
    if (sample.arcLength <= fromArcLength + kEpsilon) continue;
    if (sample.arcLength > end + kEpsilon) break;
    const bool arrival = sample.arcLength >= end - kEpsilon;
    if (!converter.advance(sample.arcLength, sample.pose, arrival)) return result;
  }
  return result;
}

JointConversionResult checkConverted(const JointConversionResult& converted, const TcpPath& path,
                                     const WaypointCheck& check) {
  if (converted.joints.empty() || converted.joints.size() != converted.arcLengths.size()) {
    throw Error("joint conversion: a conversion to check again needs its seed and one arc length per waypoint");
  }
  JointConversionResult result;
  result.joints.push_back(converted.joints.front());
  result.arcLengths.push_back(converted.arcLengths.front());
  for (std::size_t k = 1; k < converted.joints.size(); ++k) {
    const double arcLength = converted.arcLengths[k];
    if (check && !check(result.joints.back(), converted.joints[k], arcLength)) {
      result.status = ConversionStatus::Rejected;
      result.reason = stoppedAt(kRejected, arcLength, path.length());
      result.failedAtArcLength = arcLength;
      result.refused = converted.joints[k];
      return result;
    }
    result.joints.push_back(converted.joints[k]);
    result.arcLengths.push_back(arcLength);
  }
  result.status = converted.status;
  result.reason = converted.reason;
  result.failedAtArcLength = converted.failedAtArcLength;
  result.refused = converted.refused;
  return result;
}

}  // namespace arcplan::planners
