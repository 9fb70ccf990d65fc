#pragma once
// The one way a planned joint path is measured, for `plan` and `bench` alike (docs/metrics.md): the
// path is densified, time-scaled when a TCP speed limit is given, and its metrics computed; the
// clearance is evaluated at every waypoint of the densified path (consecutive waypoints at most
// 2 mm of TCP travel and 0.01 rad per joint apart), with or without time scaling.
#include <optional>

#include <nlohmann/json.hpp>

#include "arcplan/robot/robot_model.h"
#include "arcplan/trajectory/joint_path.h"
#include "arcplan/trajectory/metrics.h"
#include "arcplan/trajectory/time_scaling.h"
#include "arcplan/trajectory/timed_trajectory.h"

namespace arcplan::trajectory {

struct PathMeasurement {
  // Without time scaling only the path's metrics (TCP and joint path length, clearance) are
  // measured; the others are NaN.
  TrajectoryMetrics metrics;
  std::optional<TimedTrajectory> timed;  // the scaled trajectory, when scaling was asked for
};

// Throws arcplan::Error as scaleToTcpSpeed / densifyJointPath do (bad options, invalid path).
PathMeasurement measurePath(const robot::RobotModel& model, const JointPath& path,
                            const std::optional<TimeScalingOptions>& scaling, const ClearanceFunction& clearance = {});

// The measured metrics under their keys from metricDescriptors(): every metric of a scaled path
// (as toJson(TrajectoryMetrics)); of an unscaled one the path metrics only, min_clearance_m null when
// not finite.
nlohmann::json toJson(const PathMeasurement& measurement);

}  // namespace arcplan::trajectory
