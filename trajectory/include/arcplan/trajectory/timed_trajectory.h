#pragma once
// A joint path with timing: the path it follows, the interpolation knots with their times, and
// samples of the interpolated motion on a uniform time grid with the TCP speed profile.
#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "arcplan/trajectory/joint_path.h"

namespace arcplan::trajectory {

struct TimedTrajectory {
  // The densified path (planner waypoints kept, bounded steps) and the length of its TCP curve.
  JointPath densePath;
  double tcpPathLength = 0.0;  // m

  // PCHIP knots (one cubic per joint between consecutive knots): configurations on the dense path.
  JointPath knots;
  std::vector<double> knotTimes;  // s, strictly increasing, starts at 0

  // Samples on a uniform grid from 0 to duration() (step ≤ the check step).
  std::vector<double> time;                  // s
  std::vector<robot::Vector6> position;      // rad
  std::vector<robot::Vector6> velocity;      // rad/s
  std::vector<robot::Vector6> acceleration;  // rad/s² (PCHIP is C¹: jumps at knots)
  std::vector<double> tcpSpeed;              // m/s, |linear velocity of the tip link|
  std::vector<Eigen::Vector3d> tcpPosition;  // m, base frame

  // The limits the trajectory was scaled for (metrics compare against them).
  double tcpSpeedLimit = 0.0;                                // m/s
  robot::Vector6 jointSpeedLimits = robot::Vector6::Zero();  // rad/s

  double duration() const { return knotTimes.empty() ? 0.0 : knotTimes.back(); }
};

// Writes the samples as CSV (header t,q0..q5,qd0..qd5,qdd0..qdd5,tcp_speed,tcp_x,tcp_y,tcp_z),
// atomically.
void writeTimedTrajectoryCsv(const std::filesystem::path& file, const TimedTrajectory& trajectory);

}  // namespace arcplan::trajectory
