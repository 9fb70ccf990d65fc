#pragma once
// Time scaling of a joint path under a TCP linear-speed limit (thesis §4.3; method in docs/trajectory.md).
//
// Steps: densify the path (path_densification.h); cumulative TCP arc length by forward kinematics;
// a ramp–cruise–brake speed profile along the path, cruising at maxTcpSpeed, ramping up and braking
// with constant acceleration (maxTcpSpeed / riseTime, or maxTcpAcceleration), and slower wherever a
// joint would otherwise exceed its speed limit (the model's URDF velocity limits); times by
// integrating that profile; PCHIP knots on the dense path at uniform times of the profile and a PCHIP
// per joint in time (at rest at both ends); then a check on a uniform time grid (step ≤
// checkTimeStep) with forward kinematics and the Jacobian, stretching the time of the offending
// knot intervals until no sampled TCP speed exceeds maxTcpSpeed and no sampled joint speed exceeds
// its limit.
#include <optional>

#include "arcplan/robot/robot_model.h"
#include "arcplan/trajectory/joint_path.h"
#include "arcplan/trajectory/timed_trajectory.h"

namespace arcplan::trajectory {

struct TimeScalingOptions {
  double maxTcpSpeed = 0.25;                 // m/s, ISO/TS 15066 collaborative limit used by the thesis
  double riseTime = 0.2;                     // s, time to reach maxTcpSpeed from rest (and to brake)
  std::optional<double> maxTcpAcceleration;  // m/s², replaces maxTcpSpeed / riseTime when set
  double checkTimeStep = 0.002;              // s, grid of the verification and of the output samples
  double maxJointStep = 0.01;                // rad, densification
  double maxTcpStep = 0.002;                 // m, densification
  double smoothWaypointSpacing = 0.05;       // rad, densification: closer waypoints are joined smoothly
};

// Throws arcplan::Error naming the option for invalid options (non-positive or non-finite speed,
// rise time, acceleration or steps) and for an invalid path (fewer than 2 waypoints, non-finite
// values, joints outside the model's limits). The model must have 6 joints.
TimedTrajectory scaleToTcpSpeed(const robot::RobotModel& model, const JointPath& path,
                                const TimeScalingOptions& options = {});

// scaleToTcpSpeed(model, path, options).duration(), computed the same way without keeping the output grid's samples
// (for comparing paths by execution time: a 15 s trajectory's samples are ~1.3 MB, whose allocation and first
// touch were a seventh of its time scaling). Throws as scaleToTcpSpeed does.
double scaledDuration(const robot::RobotModel& model, const JointPath& path, const TimeScalingOptions& options = {});

// The duration of the planned ramp–cruise–brake profile alone (the steps before the PCHIP knots and their
// check), about a tenth of scaleToTcpSpeed's cost: never above scaleToTcpSpeed(model, path, options).duration()
// (beyond rounding), which only ever stretches the planned times. For telling which of several paths cannot be
// the fastest without timing each. Throws as scaleToTcpSpeed does.
double plannedDuration(const robot::RobotModel& model, const JointPath& path, const TimeScalingOptions& options = {});

}  // namespace arcplan::trajectory
