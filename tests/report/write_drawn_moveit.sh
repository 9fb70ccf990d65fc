#!/bin/bash
# Writes the drawn campaign's MoveIt problem (moveit/scene0001.yaml, moveit/request0001.yaml) into DIR, the
# campaign folder (a copy of tests/report/drawn_campaign): one object per shape kind MoveIt has — box,
# cylinder, sphere, mesh — behind arcplan's UR10e and away from its motion, and a sphere held by tool0. These are
# not MotionBenchMaker problems (MBM's are for a UR5 + Robotiq with boxes and cylinders only): written here, once,
# for test_report_scene.cpp and browser_reports.sh.
set -euo pipefail
dir="$1/moveit"
mkdir -p "$dir"
cat > "$dir/scene0001.yaml" <<'SCENE'
# One object per shape kind, all behind the robot and away from its motion, and a sphere held by tool0.
world:
  collision_objects:
    - id: crate
      pose: {position: [-0.8, 0.2, 0.3], orientation: [0, 0, 0.7071067811865476, 0.7071067811865476]}
      primitives: [{type: box, dimensions: [0.1, 0.2, 0.3]}]
      primitive_poses: [{position: [0.1, 0, 0], orientation: [0, 0, 0, 1]}]
    - id: can
      pose: {position: [-0.8, -0.3, 0.2], orientation: [0, 0, 0, 1]}
      primitives: [{type: cylinder, dimensions: [0.4, 0.05]}]
      primitive_poses: [{position: [0, 0, 0], orientation: [0.7071067811865476, 0, 0, 0.7071067811865476]}]
    - id: ball
      pose: {position: [-0.6, -0.6, 0.5], orientation: [0, 0, 0, 1]}
      primitives: [{type: sphere, dimensions: [0.07]}]
      primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]
    - id: wedge
      pose: {position: [0, 0, 0], orientation: [0, 0, 0, 1]}
      meshes:
        - vertices: [[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]
          triangles: [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
      mesh_poses: [{position: [-0.7, 0.6, 0.1], orientation: [0, 0, 0, 1]}]
robot_state:
  attached_collision_objects:
    - link_name: tool0
      object:
        id: held
        primitives: [{type: sphere, dimensions: [0.02]}]
        primitive_poses: [{position: [0, 0, 0.3], orientation: [0, 0, 0, 1]}]
SCENE
cat > "$dir/request0001.yaml" <<'REQUEST'
start_state:
  joint_state:
    name: [shoulder_pan_joint, shoulder_lift_joint, elbow_joint, wrist_1_joint, wrist_2_joint, wrist_3_joint]
    position: [0, -1.57, 1.57, -1.57, -1.57, 0]
goal_constraints:
  - joint_constraints:
      - {joint_name: shoulder_pan_joint, position: 0.5}
      - {joint_name: shoulder_lift_joint, position: -1.57}
      - {joint_name: elbow_joint, position: 1.57}
      - {joint_name: wrist_1_joint, position: -1.57}
      - {joint_name: wrist_2_joint, position: -1.57}
      - {joint_name: wrist_3_joint, position: 0}
REQUEST
