#pragma once
// Internal to the arc planner: one solve()'s query and the three ways of answering it, each in its
// own file (thesis_detours.cpp, via_point_planning.cpp, joint_space_fallback.cpp). Each returns an
// ArcOutcome — a path and how it was made, or why there is none — which ArcPlanner::solve turns into
// the planner's result once.
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/SpaceInformation.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/planners/arc_planner.h"
#include "arm_contact.h"
#include "path_validation.h"

namespace arcplan::planners::detail {

struct ArcQuery {
  const collision::CollisionModel& model;
  const std::vector<collision::Obstacle>& obstacles;
  const LinkOutlines& outlines;  // the robot's links, for the arm's contacts (arm_contact.h)
  const robot::UrInverseKinematics& ik;
  const JointConversionOptions& conversion;
  const ompl::base::PlannerTerminationCondition& ptc;
  PathValidator& validator;
  robot::Vector6 start, goal;
  Eigen::Isometry3d a, b;  // TCP poses of start and goal
  int startBranch;         // the start's IK branch (UrInverseKinematics::branchOf), which every TCP path keeps

  JointConversionResult startOnly() const;  // a walk's prefix: the start configuration at arc length 0
};

// What one way of answering found. The fields mean what ArcPlannerResult's of the same name mean.
struct ArcOutcome {
  ArcPlannerResult::Kind kind = ArcPlannerResult::Kind::Failed;
  std::string reason;           // why there is no path; empty with one
  JointConversionResult path;   // the waypoints, when kind is not Failed
  std::vector<Detour> detours;  // thesis mode
  std::vector<std::string> obstacles;
  std::vector<Eigen::Vector3d> viaPoints;
  std::vector<double> blends;
  double tcpPathLength = 0.0;
  double cartesianFraction = 0.0;
  int routesTried = 0;
  ArcPlannerResult::FallbackTimes fallbackTimes;
  double simplificationTime = 0.0;

  bool solved() const { return kind != ArcPlannerResult::Kind::Failed; }
};

// A failure that says why.
ArcOutcome failure(std::string reason);

// Thesis mode: the line A→B with a detour of exactly `shape` around each obstacle that blocks it.
ArcOutcome planThesisDetours(const ArcQuery& query, const ArcParameters& shape, double planeAngle);

// Auto mode: the shortest valid route through via points, corners blended.
ArcOutcome planViaPoints(const ArcQuery& query);

// How a joint path is timed at the planner's speed limit: its execution time (s), and a lower bound of that
// time at a fraction of its cost, to pass over paths that cannot be the fastest. Functions rather than calls into
// trajectory's time scaling, so that the strategies stay free of how a path is timed (ArcPlanner supplies
// trajectory::scaleToTcpSpeed and trajectory::plannedDuration).
struct ExecutionTiming {
  using Of = std::function<double(const std::vector<robot::Vector6>&)>;
  Of time, lowerBound;

  // True when `path` certainly takes longer than `seconds` to execute: its bound is above them by more than the
  // rounding the bound may differ from the time by where nothing stretches it.
  bool slowerThan(const std::vector<robot::Vector6>& path, double seconds) const {
    return lowerBound(path) > seconds * (1.0 + 1e-9);
  }
};

// How the fallback's RRTConnect runs: every random draw from generators seeded with `seed`, its `range`
// as RRTConnect's parameter of that name (0: RRTConnect's default).
struct JointPlanSettings {
  std::uint_fast32_t seed = 1;
  double range = 0.0;
  std::uint_fast32_t plans = 4;    // seeds seed .. seed + plans - 1 (ArcPlanner::setFallbackPlans)
  std::uint_fast32_t threads = 1;  // threads drawing the plans at once (ArcPlanner::setFallbackThreads)
};

// RRTConnect on `si` (whose validity keeps the margin), simplified as `plan` and `bench` simplify it (up to 4
// draws), each also with shortcuts for the TCP where they execute faster, the fastest kept; then of that
// joint path, its segments as TCP lines where they validate, and mixes of the two, the one of the
// shortest execution time (`timing`; its reason says which, with the times). Its reason on failure says only that
// it failed.
ArcOutcome planInJointSpace(const ArcQuery& query, const ompl::base::SpaceInformationPtr& si,
                            const JointPlanSettings& settings, const ExecutionTiming& timing);

}  // namespace arcplan::planners::detail
