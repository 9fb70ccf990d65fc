#pragma once
// A planner's own solve time as every registered planner reports it (planner_registry.h, lastSolveTime): the
// planner data's solve-time property, which OMPL's Benchmark copies into each run's properties. Internal.
#include <ompl/base/PlannerData.h>

namespace arcplan::planners::detail {

// Sets the solve-time property (trajectory::solveTimeDescriptor) of `data` to `seconds`.
void recordSolveTime(ompl::base::PlannerData& data, double seconds);

}  // namespace arcplan::planners::detail
