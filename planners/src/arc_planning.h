#pragma once
// Internal to the arc planner: one solve()'s query and the three ways of answering it, each in its
// own file (thesis_detours.cpp, via_point_planning.cpp, joint_space_fallback.cpp). Each fills the
// ArcPlannerResult it is given and returns the joint waypoints of its path (empty on failure, with
// result.reason saying why).
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/SpaceInformation.h>

#include <cstdint>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/planners/arc_planner.h"
#include "arcplan/planners/path_validation.h"

namespace arcplan::planners::detail {

struct ArcQuery {
  const collision::CollisionModel& model;
  const std::vector<collision::Obstacle>& obstacles;
  const robot::UrInverseKinematics& ik;
  const JointConversionOptions& conversion;
  const ompl::base::PlannerTerminationCondition& ptc;
  PathValidator& validator;
  robot::Vector6 start, goal;
  Eigen::Isometry3d a, b;  // TCP poses of start and goal

  JointWaypoints startOnly() const;  // a walk's prefix: the start configuration at arc length 0
};

// Thesis mode: the line A→B with a detour of exactly `shape` around each obstacle that blocks it.
JointWaypoints planThesisDetours(const ArcQuery& query, const ArcParameters& shape, double planeAngle,
                                 ArcPlannerResult& result);

// Auto mode: the shortest valid route through via points, corners blended.
JointWaypoints planViaPoints(const ArcQuery& query, ArcPlannerResult& result);

// RRTConnect on `si` (whose validity keeps the margin), simplified, its segments turned into TCP lines where they
// validate; every random draw from generators seeded with `seed`.
JointWaypoints planInJointSpace(const ArcQuery& query, const ompl::base::SpaceInformationPtr& si,
                                std::uint_fast32_t seed, ArcPlannerResult& result);

}  // namespace arcplan::planners::detail
