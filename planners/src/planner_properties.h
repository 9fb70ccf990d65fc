#pragma once
// What the registered planners write into their planner data, which OMPL's Benchmark copies into each run's
// properties: the numbers' text, and each planner's own solve time (planner_registry.h, lastSolveTime). Internal.
#include <ompl/base/PlannerData.h>

#include <string>

namespace arcplan::planners::detail {

// A planner data property's number (and a parameter's in messages): 10 significant digits, well below what the
// clocks and the measurements resolve.
std::string propertyNumber(double value);

// Sets the solve-time property (trajectory::solveTimeDescriptor) of `data` to `seconds`.
void recordSolveTime(ompl::base::PlannerData& data, double seconds);

}  // namespace arcplan::planners::detail
