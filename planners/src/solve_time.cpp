#include "solve_time.h"

#include <sstream>

#include "arcplan/trajectory/metric_descriptors.h"

namespace arcplan::planners::detail {

void recordSolveTime(ompl::base::PlannerData& data, double seconds) {
  std::ostringstream text;
  text.precision(10);  // as the arc planner's other properties: well below the clock's resolution
  text << seconds;
  data.properties[trajectory::solveTimeDescriptor().omplProperty] = text.str();
}

}  // namespace arcplan::planners::detail
