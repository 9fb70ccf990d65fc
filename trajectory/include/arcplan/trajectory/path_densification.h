#pragma once
// Resampling of a sparse joint path (an RRT path may have a handful of waypoints metres apart) into
// a dense one whose consecutive waypoints are close both in joint space and at the TCP, so that the
// TCP curve is well described by its samples and an interpolation through them stays near the
// path the planner validated.
//
// New waypoints lie on the straight joint-space segments between the original ones (the motion a
// planner's motion validator checked); every original waypoint is kept. Exact repeats are dropped.
#include <vector>

#include <Eigen/Core>

#include "arcplan/robot/robot_model.h"
#include "arcplan/trajectory/joint_path.h"

namespace arcplan::trajectory {

struct DensificationOptions {
  double maxJointStep = 0.01;  // rad, largest change of any joint between consecutive waypoints
  double maxTcpStep = 0.002;   // m, largest TCP displacement between consecutive waypoints
};

struct DensePath {
  JointPath waypoints;
  std::vector<Eigen::Vector3d> tcpPositions;  // FK of the model's tip link, base frame
  std::vector<double> tcpArcLength;           // cumulative TCP chord length, starts at 0 (m)
};

// Throws arcplan::Error for non-positive steps or a path with fewer than 2 waypoints.
DensePath densifyJointPath(const robot::RobotModel& model, const JointPath& path,
                           const DensificationOptions& options = {});

}  // namespace arcplan::trajectory
