#pragma once
// The trajectory metrics (docs/metrics.md), one implementation for `plan`, `scale` and `bench`; their
// names (JSON keys, benchmark properties, labels) are in metric_descriptors.h.
#include <functional>
#include <limits>

#include <nlohmann/json.hpp>

#include "arcplan/trajectory/joint_path.h"
#include "arcplan/trajectory/timed_trajectory.h"

namespace arcplan::trajectory {

struct TrajectoryMetrics {
  double tcpPathLength = 0.0;    // m, TCP curve of the densified path
  double jointPathLength = 0.0;  // rad, joint-space length of the planner's path
  double executionTime = 0.0;    // s
  double meanTcpSpeed = 0.0;     // m/s, tcpPathLength / executionTime
  double peakTcpSpeed = 0.0;     // m/s, largest sampled TCP speed
  double timeAboveLimit = 0.0;   // s, time with TCP speed above the trajectory's limit
  double minClearance = std::numeric_limits<double>::quiet_NaN();  // m, NaN when not computed
  double maxJointSpeedRatio = 0.0;  // max over samples and joints of |qd| / joint speed limit
};

// Smallest robot–obstacle distance at a configuration (supplied by the caller, e.g. the collision
// module, so that trajectory does not depend on it). The exact value is needed only below `enough` (the
// smallest found so far, +infinity first): at or above it any value ≥ enough will do, so that a caller may answer
// the many waypoints far from the path's closest one from cheap bounds.
using ClearanceFunction = std::function<double(const robot::Vector6& q, double enough)>;

// `path` is the planner's path (joint length); the clearance, when given, is evaluated at every
// waypoint of the trajectory's densified path.
TrajectoryMetrics computeMetrics(const JointPath& path, const TimedTrajectory& trajectory,
                                 const ClearanceFunction& clearance = {});

// The smallest clearance at the waypoints of a densified path; NaN without a clearance function. Each waypoint is
// asked once, every 16th first, each with the smallest clearance found before it.
double minClearanceAlong(const JointPath& densePath, const ClearanceFunction& clearance);

// Every trajectory metric under its key from metricDescriptors(); null for a value that is not finite
// (min_clearance_m when no clearance function was given).
nlohmann::json toJson(const TrajectoryMetrics& metrics);

}  // namespace arcplan::trajectory
