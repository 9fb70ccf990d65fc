#include "arcplan/trajectory/path_measurement.h"

#include <cmath>
#include <limits>

#include "arcplan/trajectory/metric_descriptors.h"
#include "arcplan/trajectory/path_densification.h"

namespace arcplan::trajectory {

PathMeasurement measurePath(const robot::RobotModel& model, const JointPath& path,
                            const std::optional<TimeScalingOptions>& scaling, const ClearanceFunction& clearance) {
  PathMeasurement measurement;
  if (scaling) {
    measurement.timed = scaleToTcpSpeed(model, path, *scaling);
    measurement.metrics = computeMetrics(path, *measurement.timed, clearance);
    return measurement;
  }
  // The densification a scaled trajectory would get (TimeScalingOptions' defaults).
  const TimeScalingOptions defaults;
  const DensePath dense =
      densifyJointPath(model, path, {defaults.maxJointStep, defaults.maxTcpStep, defaults.smoothWaypointSpacing});
  constexpr double notMeasured = std::numeric_limits<double>::quiet_NaN();
  TrajectoryMetrics& metrics = measurement.metrics;
  metrics.executionTime = metrics.meanTcpSpeed = metrics.peakTcpSpeed = notMeasured;
  metrics.timeAboveLimit = metrics.maxJointSpeedRatio = notMeasured;
  metrics.tcpPathLength = dense.tcpArcLength.back();
  metrics.jointPathLength = jointPathLength(path);
  metrics.minClearance = minClearanceAlong(dense.waypoints, clearance);
  return measurement;
}

nlohmann::json toJson(const PathMeasurement& measurement) {
  if (measurement.timed) return toJson(measurement.metrics);
  nlohmann::json document = nlohmann::json::object();
  for (const MetricDescriptor& metric : metricDescriptors()) {
    if (metric.member == nullptr) continue;  // the solve time is the planner's
    const double value = measurement.metrics.*metric.member;
    if (std::isfinite(value)) {
      document[metric.key] = value;
    } else if (metric.member == &TrajectoryMetrics::minClearance) {
      document[metric.key] = nullptr;  // measured, but there was nothing to measure it to
    }
  }
  return document;
}

}  // namespace arcplan::trajectory
