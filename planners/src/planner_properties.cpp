#include "planner_properties.h"

#include <sstream>

#include "arcplan/trajectory/metric_descriptors.h"

namespace arcplan::planners::detail {

std::string propertyNumber(double value) {
  std::ostringstream text;
  text.precision(10);
  text << value;
  return text.str();
}

void recordSolveTime(ompl::base::PlannerData& data, double seconds) {
  data.properties[trajectory::solveTimeDescriptor().omplProperty] = propertyNumber(seconds);
}

}  // namespace arcplan::planners::detail
