#pragma once
// What the report's 3D view needs to draw the arm: each link's collision mesh once (in the link's
// frame), and the link poses along a time-scaled trajectory from arcplan's forward kinematics, so
// the page only places meshes and never does kinematics itself.
#include <vector>

#include <nlohmann/json.hpp>

#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::report {

// [{link, positions, indices}] for every link with mesh geometry, in the model's link order:
// positions is base64 of little-endian Float32 x,y,z per vertex (m, link frame, URDF origin and
// scale applied), indices base64 of Uint32 triangle corners.
nlohmann::json robotMeshesJson(const robot::RobotModel& model);

// Link poses of the meshed links (same order as robotMeshesJson) at `rate` Hz from 0 to the last
// time, joints linearly interpolated between the given samples (times increasing, one joint vector
// each): {rate_hz, frames, duration_s, poses} with poses base64 of Float32 [frame][link]
// (x, y, z, qx, qy, qz, qw). Throws arcplan::Error when times and joints disagree or are empty.
nlohmann::json linkPoseFrames(const robot::RobotModel& model, const std::vector<double>& times,
                              const std::vector<robot::Vector6>& joints, double rate);

}  // namespace arcplan::report
