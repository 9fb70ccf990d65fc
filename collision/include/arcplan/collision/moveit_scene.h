#pragma once
// Planning problems written by MoveIt: a moveit_msgs/PlanningScene and a moveit_msgs/MotionPlanRequest
// as YAML (what `ros2 topic echo`, rosbag exports and MotionBenchMaker write), and the `.scene` text
// files RViz's Motion Planning panel exports. They become arcplan's own Scene (obstacles in the
// robot's base_link, allowed pairs) and Query (joint start and goal), so everything downstream —
// collision model, planners, benchmarks, reports — is unchanged (docs/formats.md, "MoveIt inputs").
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "arcplan/collision/scene.h"
#include "arcplan/robot/ur_description.h"

namespace arcplan::collision {

// What the messages are read against: poses are given in the robot's root frame (MoveIt's planning
// frame) or relative to one of its links, and joint and link names must be the robot's. The robot is
// a URDF, or (urDescription.type given, urdf empty) a UR type built from Universal Robots'
// description parameters, whose names are those of UR's xacro (base_link ... tool0,
// shoulder_pan_joint ... wrist_3_joint).
struct MoveItRobot {
  std::filesystem::path urdf;
  std::filesystem::path srdf;                        // optional: its disabled collision pairs (empty: none)
  robot::UrDescriptionSelection urDescription = {};  // the initializer keeps {urdf, srdf} warning-free
};

struct MoveItProblem {
  Scene scene;  // obstacles in base_link, allowed pairs, one query named after the request file (joints)
  // base_link in the messages' planning frame: maps scene poses back to the frame of the files.
  Eigen::Isometry3d baseInPlanningFrame = Eigen::Isometry3d::Identity();
  // Joint values by name, arm and others (gripper fingers): the scene's robot_state, with a request's
  // start_state over it.
  std::map<std::string, double> startState;
  // Names in the scene's allowed collision matrix that are neither a link nor an object. They are
  // accepted (and listed here) only when the matrix names every link with collision geometry, as
  // MoveIt's own export does; the extra names are links of the description it was exported from.
  std::vector<std::string> ignoredMatrixNames;
};

// A PlanningScene YAML: world.collision_objects (box, sphere, cylinder [height, radius], cone
// [height, radius] primitives and meshes; object pose composed with each primitive or mesh pose;
// header frames: the root, "world", a fixed_frame_transforms frame or a link at robot_state),
// robot_state.attached_collision_objects (bodies moving with their link), allowed_collision_matrix
// (entry and default entries). Throws arcplan::Error "file:line:column: field: what" on bad input:
// unknown primitive type, wrong dimension count, a quaternion of zero norm, an unknown frame, an
// allowed-matrix name that is no link or object (unless the matrix is complete, see above).
MoveItProblem loadMoveItScene(const std::filesystem::path& sceneFile, const MoveItRobot& robot);

// The scene (a `.scene` file is read as loadMoveItTextScene does, any other as a PlanningScene YAML)
// plus a MotionPlanRequest YAML: start_state (merged over the scene's robot_state; every
// arm joint must be given by one of them), goal_constraints[0] as joint constraints (every arm
// joint) or a position + orientation constraint on a link rigidly fixed to tool0 (solved by IK with
// the start as seed). Throws arcplan::Error naming file, line and field.
MoveItProblem loadMoveItProblem(const std::filesystem::path& sceneFile, const std::filesystem::path& requestFile,
                                const MoveItRobot& robot);

// A `.scene` text file (RViz's export; both the old layout and the one with object poses and
// subframes): objects of box, sphere, cylinder, cone and mesh shapes in the planning frame. Throws
// arcplan::Error "file:line: what expected".
MoveItProblem loadMoveItTextScene(const std::filesystem::path& sceneFile, const MoveItRobot& robot);

}  // namespace arcplan::collision
