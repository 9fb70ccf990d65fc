#pragma once
// What arcplan.Trajectory holds: a time-scaled trajectory and its metrics (docs/metrics.md), from
// arcplan.scale or a PlanResult planned with vmax.
#include "arcplan/trajectory/metrics.h"
#include "arcplan/trajectory/timed_trajectory.h"

namespace arcplan::python {

struct TrajectoryHandle {
  trajectory::TimedTrajectory timed;
  trajectory::TrajectoryMetrics metrics;
};

}  // namespace arcplan::python
