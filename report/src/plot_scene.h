#pragma once
// A campaign's plot scene (paths/<suite>/<problem>/scene.json, written by `bench`) as the 3D view
// draws it: the robot it names, its start and goal joints, and its obstacles and held bodies with
// their meshes in the page's encoding. Internal to arcplan::report.
#include <nlohmann/json.hpp>

#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/robot_source.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::report::detail {

// The robot the scene names (its "robot" entry; a scene written before there was one: the UR10e).
robot::RobotSource robotSourceOf(const nlohmann::json& scene);

// scene[key] as six joint values. Throws arcplan::Error naming the key otherwise.
robot::Vector6 jointsOf(const nlohmann::json& scene, const char* key);

// The scene with every mesh (obstacles and attached bodies) as base64 positions/indices, thinned above
// kMaxTrianglesPerMesh. With the robot, each attached body is moved to the nearest link the page draws
// (its own, or the first ancestor with geometry through fixed joints, e.g. wrist_3_link for tool0),
// its pose composed into that link's frame; a body with no such link is dropped. Without the robot
// (it did not load, so no arm is drawn) the attached bodies are dropped. Throws arcplan::Error for a
// mesh triangle naming a vertex that is not there.
nlohmann::json drawnScene(nlohmann::json scene, const robot::RobotModel* robot);

}  // namespace arcplan::report::detail
