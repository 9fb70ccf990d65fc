#include "arcplan/trajectory/metrics.h"

#include <algorithm>
#include <cmath>

#include "arcplan/trajectory/metric_descriptors.h"

namespace arcplan::trajectory {
namespace {

// Time during which the speed, linear between samples, is above the limit.
double timeAbove(const std::vector<double>& time, const std::vector<double>& speed, double limit) {
  double total = 0.0;
  for (std::size_t i = 1; i < time.size(); ++i) {
    const double a = speed[i - 1] - limit, b = speed[i] - limit, dt = time[i] - time[i - 1];
    if (a > 0.0 && b > 0.0) {
      total += dt;
    } else if (a > 0.0 || b > 0.0) {
      total += dt * std::max(a, b) / std::abs(b - a);
    }
  }
  return total;
}

}  // namespace

TrajectoryMetrics computeMetrics(const JointPath& path, const TimedTrajectory& trajectory,
                                 const ClearanceFunction& clearance) {
  TrajectoryMetrics metrics;
  metrics.tcpPathLength = trajectory.tcpPathLength;
  metrics.jointPathLength = jointPathLength(path);
  metrics.executionTime = trajectory.duration();
  metrics.meanTcpSpeed = metrics.executionTime > 0.0 ? metrics.tcpPathLength / metrics.executionTime : 0.0;
  if (!trajectory.tcpSpeed.empty()) {
    metrics.peakTcpSpeed = *std::max_element(trajectory.tcpSpeed.begin(), trajectory.tcpSpeed.end());
  }
  metrics.timeAboveLimit = timeAbove(trajectory.time, trajectory.tcpSpeed, trajectory.tcpSpeedLimit);
  for (const auto& velocity : trajectory.velocity) {
    for (int j = 0; j < 6; ++j) {
      if (trajectory.jointSpeedLimits[j] > 0.0) {
        metrics.maxJointSpeedRatio =
            std::max(metrics.maxJointSpeedRatio, std::abs(velocity[j]) / trajectory.jointSpeedLimits[j]);
      }
    }
  }
  metrics.minClearance = minClearanceAlong(trajectory.densePath, clearance);
  return metrics;
}

double minClearanceAlong(const JointPath& densePath, const ClearanceFunction& clearance) {
  if (!clearance) return std::numeric_limits<double>::quiet_NaN();
  // Every kStride-th waypoint first: on the way towards the path's closest point each waypoint would otherwise be
  // a new minimum, to be measured exactly; after a first pass the minimum so far is within a stride of the true one,
  // and the second pass may answer most waypoints from bounds (ClearanceFunction's `enough`).
  constexpr std::size_t kStride = 16;
  double minimum = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < densePath.size(); k += kStride)
    minimum = std::min(minimum, clearance(densePath[k], minimum));
  for (std::size_t k = 0; k < densePath.size(); ++k) {
    if (k % kStride != 0) minimum = std::min(minimum, clearance(densePath[k], minimum));
  }
  return minimum;
}

nlohmann::json toJson(const TrajectoryMetrics& metrics) {
  nlohmann::json document = nlohmann::json::object();
  for (const MetricDescriptor& metric : metricDescriptors()) {
    if (metric.member == nullptr) continue;  // the solve time is the planner's
    const double value = metrics.*metric.member;
    document[metric.key] = std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
  }
  return document;
}

}  // namespace arcplan::trajectory
