#pragma once
// What the report's 3D view needs to draw the arm: each link's collision mesh once (in the link's
// frame), and the link poses along a time-scaled trajectory from arcplan's forward kinematics, so
// the page only places meshes and never does kinematics itself.
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::report {

// Triangles per link above which the page gets a thinned mesh (vertex clustering): the UR arms'
// collision meshes stay whole (< 4 000 each); the MBM UR5's FTS300 sensor (43 000) and Robotiq base
// (40 000) would add 8 MB to the page and look the same (docs/report.md, "Size").
constexpr std::size_t kMaxTrianglesPerMesh = 6000;

// [{link, vertices, triangles, source_triangles, positions, indices}] for every link with collision
// geometry (meshes, and boxes, spheres and cylinders as triangles), in the model's link order: the
// arm's links and whatever hangs off the flange (tool, sensor, gripper fingers). positions is base64
// of little-endian Float32 x,y,z per vertex (m, link frame, URDF origin and scale applied), indices
// base64 of Uint32 triangle corners; source_triangles counts the link's triangles before thinning.
nlohmann::json robotMeshesJson(const robot::RobotModel& model, std::size_t maxTrianglesPerLink = kMaxTrianglesPerMesh);

// Link poses of the links robotMeshesJson draws (same order as robotMeshesJson) at `rate` Hz from 0 to the last
// time, joints linearly interpolated between the given samples (times increasing, one joint vector
// each): {rate_hz, frames, duration_s, poses} with poses base64 of Float32 [frame][link]
// (x, y, z, qx, qy, qz, qw). Throws arcplan::Error when times and joints disagree or are empty.
nlohmann::json linkPoseFrames(const robot::RobotModel& model, const std::vector<double>& times,
                              const std::vector<robot::Vector6>& joints, double rate);

}  // namespace arcplan::report
