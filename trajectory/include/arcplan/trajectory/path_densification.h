#pragma once
// Resampling of a sparse joint path (an RRT path may have a handful of waypoints metres apart) into
// a dense one whose consecutive waypoints are close both in joint space and at the TCP, so that the
// TCP curve is well described by its samples and an interpolation through them stays near the
// path the planner validated.
//
// Every original waypoint is kept; exact repeats are dropped. Between two waypoints far apart (an
// RRT edge) the new waypoints lie on the straight joint-space segment, the motion a planner's motion
// validator checked. Waypoints close together (any joint within smoothWaypointSpacing) are samples
// of a smooth curve (an arc path converted by IK every centimetre): there the new waypoints follow a
// PCHIP through the original waypoints of that run of close waypoints (one curve per run, so a long
// straight segment beside it does not bend it), parameterised by joint-space distance, so joint
// velocities do not jump at every original waypoint. PCHIP never leaves the joint box of the two waypoints
// around it, so the deviation from the straight segment is below smoothWaypointSpacing per joint
// (in practice micro-radians on a smooth path).
#include <vector>

#include <Eigen/Core>

#include "arcplan/robot/robot_model.h"
#include "arcplan/trajectory/joint_path.h"

namespace arcplan::trajectory {

struct DensificationOptions {
  double maxJointStep = 0.01;           // rad, largest change of any joint between consecutive waypoints
  double maxTcpStep = 0.002;            // m, largest TCP displacement between consecutive waypoints
  double smoothWaypointSpacing = 0.05;  // rad, see above; 0 keeps every segment straight
};

struct DensePath {
  JointPath waypoints;
  std::vector<Eigen::Vector3d> tcpPositions;  // FK of the model's tip link, base frame
  std::vector<double> tcpArcLength;           // cumulative TCP chord length, starts at 0 (m)
};

// Throws arcplan::Error for non-positive steps, a negative smoothWaypointSpacing or a path with
// fewer than 2 distinct waypoints.
DensePath densifyJointPath(const robot::RobotModel& model, const JointPath& path,
                           const DensificationOptions& options = {});

}  // namespace arcplan::trajectory
