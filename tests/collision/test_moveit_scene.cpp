// MoveIt inputs (docs/formats.md, "MoveIt inputs"): PlanningScene and MotionPlanRequest YAML and the
// `.scene` text format. Expected poses are worked out by hand from the message definitions (object
// pose · primitive pose, quaternions [x, y, z, w], cylinder [height, radius]); errors must name file:line.
#include <cmath>
#include <fstream>
#include <regex>

#include <gtest/gtest.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/robot_model.h"
#include "support/command.h"
#include "support/error_message.h"
#include "support/robot_files.h"

namespace {

using arcplan::collision::MoveItProblem;
using arcplan::collision::MoveItRobot;
using arcplan::collision::Obstacle;
using arcplan::testing::errorMessageOf;

std::filesystem::path write(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir / name) << text;
  return dir / name;
}

MoveItRobot ur10e() { return {arcplan::robot::ur10eUrdfPath(), {}}; }

// The UR10e with a stand: root link "stand", base_link 1 m above it and turned 90° about z.
MoveItRobot ur10eOnStand(const std::filesystem::path& dir) {
  std::string urdf = arcplan::testing::ur10eUrdfText();
  const std::string stand =
      "<link name=\"stand\"/><joint name=\"stand_joint\" type=\"fixed\"><parent link=\"stand\"/>"
      "<child link=\"base_link\"/><origin xyz=\"0 0 1\" rpy=\"0 0 1.5707963267948966\"/></joint>";
  urdf.insert(urdf.find("<link name=\"base_link\""), stand);
  return {write(dir, "stand.urdf", urdf), {}};
}

const Obstacle& named(const arcplan::collision::Scene& scene, const std::string& name) {
  for (const auto& obstacle : scene.obstacles) {
    if (obstacle.name == name) return obstacle;
  }
  throw std::runtime_error("no obstacle " + name);
}

TEST(MoveItScene, ObjectPoseTimesPrimitivePoseInTheBaseFrame) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_compose");
  // Object at (1, 0, 0) turned 90° about z (quaternion [0, 0, sin 45°, cos 45°]); its box 0.5 m along
  // the object's x, so at (1, 0.5, 0) in the planning frame "stand". base_link sits at (0, 0, 1) turned
  // 90°: the planning frame point (1, 0.5, 0) is (0.5, -1, -1) in base_link.
  const auto scene = write(dir, "scene.yaml", R"(
world:
  collision_objects:
    - id: crate
      header: {frame_id: stand}
      pose: {position: {x: 1, y: 0, z: 0}, orientation: {x: 0, y: 0, z: 0.7071067811865476, w: 0.7071067811865476}}
      primitives:
        - {type: box, dimensions: [0.1, 0.2, 0.3]}
        - {type: cylinder, dimensions: [0.4, 0.05]}
      primitive_poses:
        - {position: [0.5, 0, 0], orientation: [0, 0, 0, 1]}
        - {position: [0, 0, 0], orientation: [0, 0, 0, 2]}
)");
  const MoveItProblem problem = arcplan::collision::loadMoveItScene(scene, ur10eOnStand(dir));
  ASSERT_EQ(problem.scene.obstacles.size(), 2u);
  const Obstacle& box = named(problem.scene, "crate[0]");
  EXPECT_EQ(box.shape, Obstacle::Shape::Box);
  EXPECT_NEAR((box.pose.translation() - Eigen::Vector3d(0.5, -1.0, -1.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((box.size - Eigen::Vector3d(0.1, 0.2, 0.3)).norm(), 0.0, 0.0);
  // Object 90° about z, base_link 90° about z: the box is turned by 0 in base_link.
  EXPECT_NEAR((box.pose.linear() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
  const Obstacle& cylinder = named(problem.scene, "crate[1]");
  EXPECT_EQ(cylinder.shape, Obstacle::Shape::Cylinder);
  EXPECT_EQ(cylinder.length, 0.4);  // MoveIt's dimensions are [height, radius]
  EXPECT_EQ(cylinder.radius, 0.05);
  EXPECT_NEAR((cylinder.pose.translation() - Eigen::Vector3d(0.0, -1.0, -1.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((problem.baseInPlanningFrame.translation() - Eigen::Vector3d(0, 0, 1)).norm(), 0.0, 1e-12);
}

TEST(MoveItScene, BadInputNamesFileAndLine) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_errors");
  const auto load = [&](const std::string& text) {
    return errorMessageOf([&] { arcplan::collision::loadMoveItScene(write(dir, "bad.yaml", text), ur10e()); });
  };
  const std::string object = "world:\n  collision_objects:\n    - id: a\n      primitives:\n";
  EXPECT_NE(
      load(object + "        - {type: pyramid, dimensions: [1]}\n      primitive_poses: [{}]\n").find("bad.yaml:5:"),
      std::string::npos);
  EXPECT_NE(load(object + "        - {type: pyramid, dimensions: [1]}\n      primitive_poses: [{}]\n")
                .find("unknown primitive type 'pyramid'"),
            std::string::npos);
  const std::string zero = load(object +
                                "        - {type: sphere, dimensions: [0.1]}\n      primitive_poses:\n"
                                "        - {orientation: [0, 0, 0, 0]}\n");
  EXPECT_NE(zero.find("bad.yaml:7:"), std::string::npos) << zero;
  EXPECT_NE(zero.find("zero norm"), std::string::npos) << zero;
  EXPECT_NE(load(object + "        - {type: cylinder, dimensions: [0.1]}\n      primitive_poses: [{}]\n")
                .find("[height, radius]"),
            std::string::npos);
  // A hand-written matrix (not naming every link) with a name that is no link or object: a typo.
  const std::string typo = load(
      "allowed_collision_matrix:\n  entry_names: [base_link_inertia, shoulder_lnk]\n"
      "  entry_values: [[false, true], [true, false]]\n");
  EXPECT_NE(typo.find("bad.yaml:2:"), std::string::npos) << typo;
  EXPECT_NE(typo.find("'shoulder_lnk' is no link"), std::string::npos) << typo;
  EXPECT_NE(load("world:\n  collision_objects:\n    - id: a\n      header: {frame_id: nowhere}\n"
                 "      primitives: [{type: box, dimensions: [1, 1, 1]}]\n      primitive_poses: [{}]\n")
                .find("unknown frame 'nowhere'"),
            std::string::npos);
}

TEST(MoveItScene, MatrixPairsBecomeAllowedAndACompleteMatrixMayNameOldLinks) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_matrix");
  // Every UR10e link with collision geometry, plus "box_link" that this robot does not have.
  const std::vector<std::string> links = {"base_link_inertia", "shoulder_link", "upper_arm_link",
                                          "forearm_link",      "wrist_1_link",  "wrist_2_link",
                                          "wrist_3_link",      "box_link",      "post"};
  std::string names, rows;
  for (std::size_t i = 0; i < links.size(); ++i) {
    names += (i ? ", " : "") + links[i];
    rows += "    - [";
    for (std::size_t j = 0; j < links.size(); ++j) {
      const bool allowed = (links[i] == "post" && links[j] == "base_link_inertia") ||
                           (links[j] == "post" && links[i] == "base_link_inertia");
      rows += std::string(j ? ", " : "") + (allowed ? "true" : "false");
    }
    rows += "]\n";
  }
  const auto scene = write(dir, "scene.yaml",
                           "world:\n  collision_objects:\n    - id: post\n"
                           "      primitives: [{type: cylinder, dimensions: [1, 0.2]}]\n"
                           "      primitive_poses: [{position: [0, 0, 0]}]\n"
                           "allowed_collision_matrix:\n  entry_names: [" +
                               names + "]\n  entry_values:\n" + rows);
  const MoveItProblem problem = arcplan::collision::loadMoveItScene(scene, ur10e());
  EXPECT_EQ(problem.ignoredMatrixNames, std::vector<std::string>{"box_link"});
  ASSERT_EQ(problem.scene.allowedCollisions.size(), 1u);
  // The post stands through the robot's base: only the allowed pair keeps the base from colliding.
  const auto model = arcplan::collision::makeCollisionModel(problem.scene);
  arcplan::collision::CollisionData data(*model);
  const auto report = arcplan::collision::collide(*model, data, arcplan::robot::JointVector::Zero(6));
  for (const auto& [a, b] : report.collisions) EXPECT_NE(a + b, "base_link_inertiapost");
}

TEST(MoveItRequest, JointGoalAndStartFromTheRequestOverTheSceneState) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_request");
  const auto scene = write(dir, "scene0001.yaml",
                           "robot_state:\n  joint_state:\n    name: [shoulder_pan_joint, elbow_joint]\n"
                           "    position: [0.5, 1.0]\n");
  const auto request = write(dir, "request0001.yaml", R"(
start_state:
  joint_state:
    name: [shoulder_lift_joint, elbow_joint, wrist_1_joint, wrist_2_joint, wrist_3_joint]
    position: [-1.5, 1.5, -1.0, -1.57, 0.25]
goal_constraints:
  - joint_constraints:
      - {joint_name: shoulder_pan_joint, position: 0.1}
      - {joint_name: shoulder_lift_joint, position: -1.2}
      - {joint_name: elbow_joint, position: 1.3}
      - {joint_name: wrist_1_joint, position: -1.4}
      - {joint_name: wrist_2_joint, position: -1.5}
      - {joint_name: wrist_3_joint, position: 0.6}
)");
  const MoveItProblem problem = arcplan::collision::loadMoveItProblem(scene, request, ur10e());
  ASSERT_EQ(problem.scene.queries.size(), 1u);
  const auto& query = problem.scene.queries.front();
  EXPECT_EQ(query.name, "request0001");
  arcplan::robot::Vector6 start, goal;
  start << 0.5, -1.5, 1.5, -1.0, -1.57, 0.25;  // pan from the scene, elbow overridden by the request
  goal << 0.1, -1.2, 1.3, -1.4, -1.5, 0.6;
  EXPECT_EQ(*query.start.joints, start);
  EXPECT_EQ(*query.goal.joints, goal);

  const auto missing = write(dir, "request0002.yaml",
                             "start_state:\n  joint_state:\n    name: [shoulder_lift_joint]\n    position: [0]\n"
                             "goal_constraints: [{joint_constraints: [{joint_name: elbow_joint, position: 0}]}]\n");
  const std::string error =
      errorMessageOf([&] { arcplan::collision::loadMoveItProblem(dir / "x.yaml", missing, ur10e()); });
  EXPECT_NE(error.find("x.yaml"), std::string::npos) << error;  // the scene file does not exist
  write(dir, "empty.yaml", "name: empty\n");
  const std::string joint =
      errorMessageOf([&] { arcplan::collision::loadMoveItProblem(dir / "empty.yaml", missing, ur10e()); });
  EXPECT_NE(joint.find("request0002.yaml:"), std::string::npos) << joint;
  EXPECT_NE(joint.find("'shoulder_pan_joint' is missing from the start state"), std::string::npos) << joint;
}

TEST(MoveItRequest, PoseGoalOfTheFlangeBecomesAToolPose) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_pose_goal");
  const auto scene = write(dir, "scene.yaml", "name: s\n");
  // tool0 at (0.6, 0.2, 0.4), z down: a rotation of 180° about x (quaternion [1, 0, 0, 0]).
  const auto request = write(dir, "request.yaml", R"(
start_state: {joint_state: {name: [shoulder_pan_joint, shoulder_lift_joint, elbow_joint, wrist_1_joint, wrist_2_joint, wrist_3_joint], position: [0, -1.57, 1.57, -1.57, -1.57, 0]}}
goal_constraints:
  - position_constraints:
      - link_name: tool0
        constraint_region: {primitive_poses: [{position: [0.6, 0.2, 0.4]}]}
    orientation_constraints:
      - {link_name: tool0, orientation: [1, 0, 0, 0]}
)");
  const auto query = arcplan::collision::loadMoveItProblem(scene, request, ur10e()).scene.queries.front();
  ASSERT_TRUE(query.goal.pose.has_value());
  const auto& pose = *query.goal.pose;
  EXPECT_NEAR(pose[0], 0.6, 1e-12);
  EXPECT_NEAR(pose[1], 0.2, 1e-12);
  EXPECT_NEAR(pose[2], 0.4, 1e-12);
  EXPECT_NEAR(std::abs(pose[3]), M_PI, 1e-9);  // roll ±pi, pitch 0, yaw 0
  EXPECT_NEAR(pose[4], 0.0, 1e-9);
  EXPECT_NEAR(pose[5], 0.0, 1e-9);
}

TEST(MoveItScene, AttachedBodyMovesWithItsLink) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_attached");
  // A 5 cm ball held 10 cm in front of tool0, and a ball obstacle where FK puts that point at q = 0.
  const arcplan::robot::RobotModel& robot = arcplan::robot::ur10e();
  const Eigen::Vector3d held =
      arcplan::robot::tipPose(robot, arcplan::robot::JointVector::Zero(6)) * Eigen::Vector3d(0, 0, 0.1);
  const auto scene =
      write(dir, "scene.yaml",
            "world:\n  collision_objects:\n    - id: target\n"
            "      primitives: [{type: sphere, dimensions: [0.02]}]\n"
            "      primitive_poses: [{position: [" +
                std::to_string(held.x()) + ", " + std::to_string(held.y()) + ", " + std::to_string(held.z()) +
                "]}]\n"
                "robot_state:\n  attached_collision_objects:\n    - link_name: tool0\n"
                "      touch_links: [wrist_3_link]\n      object:\n        id: part\n"
                "        primitives: [{type: sphere, dimensions: [0.05]}]\n"
                "        primitive_poses: [{position: [0, 0, 0.1]}]\n");
  const MoveItProblem problem = arcplan::collision::loadMoveItScene(scene, ur10e());
  ASSERT_EQ(problem.scene.attachedObstacles.size(), 1u);
  const auto model = arcplan::collision::makeCollisionModel(problem.scene);
  arcplan::collision::CollisionData data(*model);
  const auto atZero = arcplan::collision::collide(*model, data, arcplan::robot::JointVector::Zero(6));
  EXPECT_NE(std::find(atZero.collisions.begin(), atZero.collisions.end(),
                      std::pair<std::string, std::string>("part", "target")),
            atZero.collisions.end());
  arcplan::robot::JointVector turned = arcplan::robot::JointVector::Zero(6);
  turned[0] = 0.5;  // the whole arm turns away: the held ball leaves the obstacle
  const auto away = arcplan::collision::collide(*model, data, turned);
  for (const auto& [a, b] : away.collisions) EXPECT_NE(b, "target");
}

// Found by the fuzz seeds of the hand-written problems: an absent list and a header that is no mapping
// were yaml-cpp exceptions (InvalidNode, BadSubscript) instead of arcplan errors naming the place.
TEST(MoveItScene, AbsentMatrixValuesAndScalarHeadersAreErrorsWithTheirLine) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_fuzz_found");
  const auto scene = write(dir, "scene.yaml", "allowed_collision_matrix:\n  default_entry_names: [base_link]\n");
  const std::string matrix = errorMessageOf([&] { arcplan::collision::loadMoveItScene(scene, ur10e()); });
  EXPECT_NE(matrix.find("scene.yaml:2:"), std::string::npos) << matrix;
  EXPECT_NE(matrix.find("default_entry_values: expected a list of 1 true/false values"), std::string::npos) << matrix;
  const auto empty = write(dir, "empty.yaml", "world: {collision_objects: []}\n");
  const auto request = write(
      dir, "request.yaml",
      R"(start_state: {joint_state: {name: [shoulder_pan_joint, shoulder_lift_joint, elbow_joint, wrist_1_joint, wrist_2_joint, wrist_3_joint], position: [0, -1.57, 1.57, -1.57, -1.57, 0]}}
goal_constraints:
  - position_constraints:
      - link_name: tool0
        header: base_link
        constraint_region: {primitive_poses: [{position: [0.5, 0.2, 0.5]}]}
    orientation_constraints: [{link_name: tool0, orientation: [1, 0, 0, 0]}]
)");
  const std::string header = errorMessageOf([&] { arcplan::collision::loadMoveItProblem(empty, request, ur10e()); });
  EXPECT_NE(header.find("request.yaml:5:"), std::string::npos) << header;
  EXPECT_NE(header.find("header"), std::string::npos) << header;
}

// The readers cache a description per process (file_content.h): a URDF rewritten in place, with the same
// size and modification time, is read again, not served from the cache.
TEST(MoveItScene, AUrdfRewrittenInPlaceIsReadAgain) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_urdf_rewritten");
  const MoveItRobot robot = ur10eOnStand(dir);
  const auto sceneIn = [&](const std::string& frame) {
    return write(dir, frame + ".yaml",
                 "world:\n  collision_objects:\n    - id: a\n      header: {frame_id: " + frame +
                     "}\n      primitives: [{type: sphere, dimensions: [0.1]}]\n      primitive_poses: [{}]\n");
  };
  EXPECT_EQ(arcplan::collision::loadMoveItScene(sceneIn("stand"), robot).scene.obstacles.size(), 1u);
  std::string urdf = arcplan::testing::readFile(robot.urdf);
  const auto size = std::filesystem::file_size(robot.urdf);
  const auto written = std::filesystem::last_write_time(robot.urdf);
  urdf = std::regex_replace(urdf, std::regex("\"stand\""), "\"stool\"");  // the root link renamed, same length
  write(robot.urdf.parent_path(), robot.urdf.filename().string(), urdf);
  std::filesystem::last_write_time(robot.urdf, written);
  ASSERT_EQ(std::filesystem::file_size(robot.urdf), size);
  EXPECT_EQ(arcplan::collision::loadMoveItScene(sceneIn("stool"), robot).scene.obstacles.size(), 1u);
  EXPECT_NE(errorMessageOf([&] {
              arcplan::collision::loadMoveItScene(sceneIn("stand"), robot);
            }).find("unknown frame 'stand'"),
            std::string::npos);
}

TEST(MoveItTextScene, OldAndNewLayoutsGiveTheSameObstacles) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_text");
  const auto older = write(dir, "old.scene",
                           "bench\n* table\n1\nbox\n1 0.5 0.04\n0.6 0 -0.02\n0 0 0 1\n0.5 0.5 0.5 1\n"
                           "* can\n1\ncylinder\n0.03 0.12\n0.5 0.1 0.06\n0 0 0 1\n0 0 0 0\n.\n");
  // The newer layout: object pose lines and a subframe count; shapes relative to the object.
  const auto newer = write(dir, "new.scene",
                           "bench+\n* table\n0.6 0 0\n0 0 0 1\n1\nbox\n1 0.5 0.04\n0 0 -0.02\n0 0 0 1\n0 0 0 0\n0\n"
                           "* can\n0.5 0.1 0\n0 0 0 1\n1\ncylinder\n0.03 0.12\n0 0 0.06\n0 0 0 1\n0 0 0 0\n0\n.\n");
  for (const auto& file : {older, newer}) {
    const auto scene = arcplan::collision::loadMoveItTextScene(file, ur10e()).scene;
    ASSERT_EQ(scene.obstacles.size(), 2u) << file;
    EXPECT_EQ(scene.name, "bench");
    EXPECT_NEAR((named(scene, "table").pose.translation() - Eigen::Vector3d(0.6, 0, -0.02)).norm(), 0.0, 1e-12);
    EXPECT_EQ(named(scene, "can").radius, 0.03);  // the text format writes cylinders as radius, length
    EXPECT_EQ(named(scene, "can").length, 0.12);
    EXPECT_NEAR((named(scene, "can").pose.translation() - Eigen::Vector3d(0.5, 0.1, 0.06)).norm(), 0.0, 1e-12);
  }
  const auto bad = write(dir, "bad.scene", "x\n* a\n1\nbox\n1 1 1\n0 0 0\n0 0 0 0\n0 0 0 0\n.\n");
  const std::string error = errorMessageOf([&] { arcplan::collision::loadMoveItTextScene(bad, ur10e()); });
  EXPECT_NE(error.find("bad.scene:7:"), std::string::npos) << error;
  const auto truncated = write(dir, "cut.scene", "x\n* a\n1\nbox\n1 1 1\n");
  EXPECT_NE(errorMessageOf([&] { arcplan::collision::loadMoveItTextScene(truncated, ur10e()); }).find("ends"),
            std::string::npos);
}

TEST(MoveItTextScene, WithARequestItIsAProblemThatPlanPlans) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_text_request");
  // The table's top 15 mm below base_link: the arm keeps the arc planner's 1 cm clearance everywhere.
  const auto scene =
      write(dir, "bench.scene", "bench\n* table\n1\nbox\n1 0.5 0.04\n0.6 0 -0.035\n0 0 0 1\n0.5 0.5 0.5 1\n.\n");
  const auto request = write(dir, "request.yaml", R"(
start_state: {joint_state: {name: [shoulder_pan_joint, shoulder_lift_joint, elbow_joint, wrist_1_joint, wrist_2_joint, wrist_3_joint], position: [0, -1.57, 1.57, -1.57, -1.57, 0]}}
goal_constraints:
  - joint_constraints:
      - {joint_name: shoulder_pan_joint, position: 0.5}
      - {joint_name: shoulder_lift_joint, position: -1.57}
      - {joint_name: elbow_joint, position: 1.57}
      - {joint_name: wrist_1_joint, position: -1.57}
      - {joint_name: wrist_2_joint, position: -1.57}
      - {joint_name: wrist_3_joint, position: 0}
)");
  const MoveItProblem problem = arcplan::collision::loadMoveItProblem(scene, request, ur10e());
  ASSERT_EQ(problem.scene.obstacles.size(), 1u);  // read as a .scene file (the YAML reader would refuse it)
  EXPECT_NEAR((named(problem.scene, "table").pose.translation() - Eigen::Vector3d(0.6, 0, -0.035)).norm(), 0.0, 1e-12);
  ASSERT_TRUE(problem.scene.queries.front().goal.joints.has_value());
  EXPECT_EQ((*problem.scene.queries.front().goal.joints)[0], 0.5);
  // The same through `plan`, with a TCP 0.1 m beyond tool0 for the arc planner.
  const auto json = dir / "plan.json";
  const auto result =
      arcplan::testing::runArcplan({"plan", "--moveit-scene", scene.string(), "--moveit-request", request.string(),
                                    "--urdf", arcplan::robot::ur10eUrdfPath().string(), "--tcp-offset", "0,0,0.1,0,0,0",
                                    "--planner", "arc", "--json", json.string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const std::string text = arcplan::testing::readFile(json);
  EXPECT_NE(text.find("\"status\": \"exact\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"goal_valid\": true"), std::string::npos) << text;
}

}  // namespace
