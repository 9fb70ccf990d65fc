#include "arcplan/trajectory/metric_descriptors.h"

#include "arcplan/common/error.h"

namespace arcplan::trajectory {

const std::vector<MetricDescriptor>& metricDescriptors() {
  using M = TrajectoryMetrics;
  static const std::vector<MetricDescriptor> table{
      {&M::executionTime,
       "execution_time_s",
       "s",
       "execution time REAL",
       {"execution_time"},
       "execution time (s)",
       true},
      {&M::tcpPathLength,
       "tcp_path_length_m",
       "m",
       "tcp path length REAL",
       {"tcp_path_length"},
       "TCP path length (m)",
       true},
      {&M::jointPathLength,
       "joint_path_length_rad",
       "rad",
       "",
       {"simplified_solution_length", "solution_length"},
       "joint path length (rad)",
       true},
      {nullptr, "solve_time_s", "s", "solve time REAL", {"solve_time"}, "solve time (s)", true},
      {&M::meanTcpSpeed,
       "mean_tcp_speed_mps",
       "m/s",
       "mean tcp speed REAL",
       {"mean_tcp_speed"},
       "mean TCP speed (m/s)",
       false},
      {&M::peakTcpSpeed,
       "peak_tcp_speed_mps",
       "m/s",
       "peak tcp speed REAL",
       {"peak_tcp_speed"},
       "peak TCP speed (m/s)",
       true},
      {&M::timeAboveLimit,
       "time_above_limit_s",
       "s",
       "time above limit REAL",
       {"time_above_limit"},
       "time above limit (s)",
       true},
      {&M::minClearance, "min_clearance_m", "m", "min clearance REAL", {"min_clearance"}, "min clearance (m)", false},
      {&M::maxJointSpeedRatio,
       "max_joint_speed_ratio",
       "1",
       "max joint speed ratio REAL",
       {"max_joint_speed_ratio"},
       "max joint speed ratio",
       true},
  };
  return table;
}

const MetricDescriptor& metricDescriptor(const std::string& key) {
  for (const auto& descriptor : metricDescriptors()) {
    if (descriptor.key == key) return descriptor;
  }
  throw Error("unknown trajectory metric '" + key + "'");
}

const MetricDescriptor& metricDescriptor(double TrajectoryMetrics::*member) {
  for (const auto& descriptor : metricDescriptors()) {
    if (descriptor.member == member) return descriptor;
  }
  throw Error("trajectory metric without a row in the metric table");
}

const MetricDescriptor& solveTimeDescriptor() { return metricDescriptor(nullptr); }

}  // namespace arcplan::trajectory
