#include "arcplan/benchmarks/solution_policy.h"

#include <string>

#include "arcplan/common/text_formatting.h"
#include "arcplan/common/text_parsing.h"
#include "arcplan/planners/planner_registry.h"

namespace arcplan::benchmarks {

bool simplifiesSolution(const std::string& plannerName) { return !planners::isArcPlanner(plannerName); }

void keepProblemClearance(ompl::base::Planner& planner, double clearance, bool clearanceGiven) {
  std::string own;
  if (clearanceGiven || !planner.params().getParam("clearance", own)) return;
  // Exactly the problem's value: the parameter's text is parsed back to the same double.
  const std::optional<double> value = parseDouble(own);
  if (value && *value > clearance) planner.params().setParam("clearance", formatNumber(clearance, 17));
}

}  // namespace arcplan::benchmarks
