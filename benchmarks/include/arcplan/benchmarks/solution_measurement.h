#pragma once
// A planner's solution measured and judged: the one way `plan`, Python's `arcplan.plan` (plan_query.h)
// and `bench` (every run of a campaign) do it. The path is measured by trajectory::measurePath
// (densified, time-scaled when a TCP speed limit is given) with the obstacle clearance at every dense
// waypoint, and judged by the clearance its problem asked for, relaxed in the approach zones of a start
// or goal that is itself closer (collision/endpoint_clearance.h): each dense waypoint must keep what
// stateClearanceAt asks of that state as the one rule reads it (collision::clearanceOf: from obstacles, and
// between the robot's own bodies up to collision::kSelfClearance), as the problem's validity checker asks of
// every state (the motion validator certifies every state of a motion for that too).
#include <limits>
#include <optional>

#include "arcplan/planners/planning_problem.h"
#include "arcplan/trajectory/joint_path.h"
#include "arcplan/trajectory/path_measurement.h"
#include "arcplan/trajectory/time_scaling.h"

namespace arcplan::benchmarks {

struct MeasuredSolution {
  trajectory::PathMeasurement measurement;
  // The smallest (measured − required) clearance over the dense waypoints [m], measured as collision::clearanceOf
  // (obstacles; self pairs only below kSelfClearance); +inf when nothing is near.
  double clearanceMargin = std::numeric_limits<double>::infinity();
  // Not kept: the path came closer than required somewhere; bench withdraws OMPL's "solved" for it.
  bool keptClearance() const { return !(clearanceMargin < 0.0); }
};

// `problem` is the one the path was planned in (makePlanningProblem: its collision model and required
// clearance). Throws arcplan::Error as trajectory::measurePath does (a path that cannot be time-scaled).
MeasuredSolution measureSolution(const planners::PlanningProblem& problem, const trajectory::JointPath& path,
                                 const std::optional<trajectory::TimeScalingOptions>& scaling);

}  // namespace arcplan::benchmarks
