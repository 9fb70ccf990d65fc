#include "arcplan/benchmarks/solution_policy.h"

#include "arcplan/planners/planner_registry.h"

namespace arcplan::benchmarks {

bool simplifiesSolution(const std::string& plannerName) { return !planners::isArcPlanner(plannerName); }

}  // namespace arcplan::benchmarks
