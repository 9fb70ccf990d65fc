#include "arcplan/benchmarks/run_record.h"

#include <cmath>

#include "arcplan/trajectory/metric_descriptors.h"

namespace arcplan::benchmarks {

bool RunRecord::succeeded() const {
  return solved && value(trajectory::metricDescriptor(&trajectory::TrajectoryMetrics::executionTime).key).has_value();
}

std::optional<double> RunRecord::value(const std::string& key) const {
  const auto found = values.find(key);
  if (found == values.end() || !std::isfinite(found->second)) return std::nullopt;
  return found->second;
}

}  // namespace arcplan::benchmarks
