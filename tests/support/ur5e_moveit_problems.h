#pragma once
// Hand-written MoveIt problems (moveit_msgs/PlanningScene + MotionPlanRequest YAML) for a UR5e built from UR's
// description parameters (`--ur-type ur5e`), written at run time in MotionBenchMaker's layout: one family folder
// per kind of scene, sceneNNNN.yaml / requestNNNN.yaml pairs. Between them they use every shape and field the
// MoveIt readers claim (box, cylinder [height, radius], sphere, cone, mesh, object and primitive poses, frames
// world / base_link / base_link_inertia / a link at the robot state / a fixed frame, attached objects with
// touch links, matrix and default entries) on family names MBM's data does not have. MBM's own problems (a UR5
// with a Robotiq 85, boxes and cylinders only) are read from $ARCPLAN_SHARED_DATA/mbm_ur5 by the tests that
// need them; a UR type built from the description refuses their gripper joints by name.
#include <array>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace arcplan::testing {

// The UR5e's home posture as a moveit_msgs/RobotState joint_state (2-space indent): every scene's robot state
// and every request's start.
inline std::string homeJointState() {
  return "  joint_state:\n"
         "    name: [shoulder_pan_joint, shoulder_lift_joint, elbow_joint, wrist_1_joint, wrist_2_joint, "
         "wrist_3_joint]\n"
         "    position: [0, -1.57, 1.57, -1.57, -1.57, 0]\n";
}

// A cage around the UR5e: floor (fixed frame "cell"), a post, a ball, a wedge (mesh), a probe held on tool0;
// ACM matrix and default entries.
inline std::string cageScene() {
  return R"(name: cage
robot_model_name: ur5e
fixed_frame_transforms:
  - child_frame_id: cell
    transform: {translation: [0, 0, -0.02], rotation: [0, 0, 0, 1]}
robot_state:
)" + homeJointState() +
         R"(  attached_collision_objects:
    - link_name: tool0
      touch_links: [wrist_3_link]
      object:
        id: probe
        header: {frame_id: tool0}
        primitives:
          - {type: cylinder, dimensions: [0.06, 0.01]}
        primitive_poses:
          - {position: [0, 0, 0.03], orientation: [0, 0, 0, 1]}
world:
  collision_objects:
    - id: floor
      header: {frame_id: cell}
      primitives:
        - {type: box, dimensions: [2, 2, 0.02]}
      primitive_poses:
        - {position: [0, 0, -0.01]}
    - id: post
      header: {frame_id: world}
      pose: {position: [-0.5, -0.5, 0], orientation: [0, 0, 0, 1]}
      primitives:
        - type: cylinder
          dimensions: [1.0, 0.05]
      primitive_poses:
        - position: {x: 0, y: 0, z: 0.5}
          orientation: {x: 0, y: 0, z: 0, w: 1}
    - id: ball
      header: {frame_id: base_link_inertia}
      primitives:
        - {type: sphere, dimensions: [0.05]}
      primitive_poses:
        - {position: [-0.4, -0.45, 0.45], orientation: [0, 0, 0, 1]}
    - id: wedge
      header: {frame_id: base_link}
      pose: {position: [0.6, -0.3, 0], orientation: [0, 0, 0.3826834323650898, 0.9238795325112867]}
      meshes:
        - vertices: [[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]
          triangles:
            - {vertex_indices: [0, 2, 1]}
            - {vertex_indices: [0, 1, 3]}
            - {vertex_indices: [0, 3, 2]}
            - {vertex_indices: [1, 2, 3]}
      mesh_poses:
        - {position: [0, 0, 0], orientation: [0, 0, 0, 1]}
allowed_collision_matrix:
  entry_names: [probe, ball, wrist_3_link]
  entry_values:
    - [false, false, true]
    - [false, false, false]
    - [true, false, false]
  default_entry_names: [floor]
  default_entry_values: [false]
)";
}

// A MotionPlanRequest from the home posture (homeJointState) to a joint goal, for any UR arm (the same joint names):
// one joint constraint per joint, in chain order.
inline std::string jointGoalRequest(const std::array<double, 6>& goal) {
  static const char* const names[] = {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                      "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};
  std::ostringstream text;
  text << "start_state:\n" << homeJointState() << "goal_constraints:\n  - joint_constraints:\n";
  for (std::size_t j = 0; j < goal.size(); ++j)
    text << "      - {joint_name: " << names[j] << ", position: " << goal[j] << "}\n";
  return text.str();
}

// Joint goal from the UR5e's home posture.
inline std::string cageRequest() {
  return "group_name: manipulator\nplanner_id: RRTConnect\nallowed_planning_time: 5\nnum_planning_attempts: 1\n" +
         jointGoalRequest({1.2, -1.2, 1.3, -1.67, -1.57, 0.3});
}

// A shelf board with a cone and a can on it (frames: world, a fixed frame, shoulder_link at the robot state).
inline std::string shelfPickScene() {
  return R"(name: shelf_pick
robot_state:
)" + homeJointState() +
         R"(world:
  collision_objects:
    - id: shelf
      header: {frame_id: world}
      pose: {position: [0.1, 0.75, 0], orientation: [0, 0, 0, 1]}
      primitives:
        - {type: box, dimensions: [0.5, 0.3, 0.02]}
        - {type: box, dimensions: [0.02, 0.3, 0.25]}
        - {type: box, dimensions: [0.02, 0.3, 0.25]}
      primitive_poses:
        - {position: [0, 0, 0.25]}
        - {position: [-0.26, 0, 0.125]}
        - {position: [0.26, 0, 0.125]}
    - id: cone
      header: {frame_id: shelf_frame}
      primitives:
        - {type: 4, dimensions: [0.1, 0.04]}
      primitive_poses:
        - {position: [0.18, 0, 0.31], orientation: [0, 0, 0, 1]}
    - id: can
      header: {frame_id: shoulder_link}
      operation: ADD
      primitives:
        - {type: CYLINDER, dimensions: [0.12, 0.03]}
      primitive_poses:
        - {position: [-0.15, 0.75, 0.155]}
fixed_frame_transforms:
  - child_frame_id: shelf_frame
    transform: {translation: {x: 0.1, y: 0.75, z: 0}, rotation: {x: 0, y: 0, z: 0, w: 1}}
)";
}

// Pose goal on tool0 (position and orientation constraints), picked from above.
inline std::string shelfPickRequest() {
  return R"(group_name: manipulator
start_state:
)" + homeJointState() +
         R"(goal_constraints:
  - position_constraints:
      - link_name: tool0
        header: {frame_id: base_link}
        constraint_region:
          primitives: [{type: sphere, dimensions: [0.001]}]
          primitive_poses: [{position: [0.109, 0.648, 0.42]}]
    orientation_constraints:
      - link_name: tool0
        header: {frame_id: base_link}
        orientation: [0.9443, -0.3291, 0, 0]
)";
}

// Writes the two families (cage_ur5e, shelf_pick_ur5e, problem 0001 each) under `folder` and returns it.
inline std::filesystem::path writeUr5eMoveItProblems(const std::filesystem::path& folder) {
  const auto write = [&](const std::string& family, const std::string& file, const std::string& text) {
    std::filesystem::create_directories(folder / family);
    std::ofstream out(folder / family / file);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + (folder / family / file).string());
  };
  write("cage_ur5e", "scene0001.yaml", cageScene());
  write("cage_ur5e", "request0001.yaml", cageRequest());
  write("shelf_pick_ur5e", "scene0001.yaml", shelfPickScene());
  write("shelf_pick_ur5e", "request0001.yaml", shelfPickRequest());
  return folder;
}

}  // namespace arcplan::testing
