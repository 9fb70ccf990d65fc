#pragma once
// A joint path: the waypoints a planner returns, in order, without timing. It is what `arcplan plan
// --path-csv` writes and `arcplan scale` reads.
//
// CSV format: a header line `q0,q1,q2,q3,q4,q5`, then one waypoint per line (joint angles in rad,
// joint order shoulder_pan .. wrist_3). Lines starting with `#` and blank lines are ignored.
#include <filesystem>
#include <string>
#include <vector>

#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::trajectory {

using JointPath = std::vector<robot::Vector6>;

// Reads a path file. Throws arcplan::Error naming the file and line for: a missing or wrong
// header, a wrong number of columns, a field that is not a number, NaN/inf, and a path with
// fewer than 2 waypoints.
JointPath readJointPathCsv(const std::filesystem::path& file);
// Same, and also checks every waypoint against the model's joint position limits (file and line
// of the first offending waypoint in the message).
JointPath readJointPathCsv(const std::filesystem::path& file, const robot::RobotModel& model);

// Writes the path atomically (temporary file + rename) with round-trip precision.
void writeJointPathCsv(const std::filesystem::path& file, const JointPath& path);

// Throws arcplan::Error (prefixed with `source`, e.g. "path") when the path has fewer than 2
// waypoints, a non-finite value, or a joint outside the model's position limits.
void validateJointPath(const robot::RobotModel& model, const JointPath& path, const std::string& source);

// Sum of the Euclidean joint-space distances between consecutive waypoints (rad).
double jointPathLength(const JointPath& path);

}  // namespace arcplan::trajectory
