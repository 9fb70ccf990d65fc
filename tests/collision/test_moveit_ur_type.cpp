// MoveIt problems read against a UR type built from Universal Robots' description parameters (no URDF):
// `plan --moveit-scene ... --ur-type T`, suites' `moveit_problems: {ur_type: T}`, and the hand-written
// problem families of support/ur5e_moveit_problems.h (every shape and field the readers claim, family
// names MBM does not have). Expected poses come from the message definitions and UR's xacro
// convention (base_link_inertia is base_link turned by pi about z), names from the description files.
#include <cmath>
#include <fstream>
#include <random>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "arcplan/benchmarks/moveit_problems.h"
#include "arcplan/benchmarks/plan_query.h"
#include "arcplan/benchmarks/suite.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/ur_description.h"
#include "arcplan/robot/ur_inverse_kinematics.h"
#include "support/command.h"
#include "support/error_message.h"
#include "support/ur5e_moveit_problems.h"

namespace {

namespace fs = std::filesystem;
using arcplan::collision::MoveItProblem;
using arcplan::collision::MoveItRobot;
using arcplan::collision::Obstacle;

// The hand-written UR5e families (support/ur5e_moveit_problems.h), written once per test process.
const fs::path& problems() {
  static const fs::path folder =
      arcplan::testing::writeUr5eMoveItProblems(arcplan::testing::freshTempDirectory("ur5e_moveit_problems"));
  return folder;
}

MoveItRobot urType(const std::string& type) { return {{}, {}, {type, {}, {}}}; }

const Obstacle& named(const arcplan::collision::Scene& scene, const std::string& name) {
  for (const auto& obstacle : scene.obstacles) {
    if (obstacle.name == name) return obstacle;
  }
  throw std::runtime_error("no obstacle " + name);
}

std::set<std::string> linkNamesOf(const arcplan::robot::RobotModel& model) {
  std::set<std::string> names;
  for (const auto& link : model.links()) names.insert(link.name);
  return names;
}

TEST(MoveItUrType, FramesAndNamesAreTheDescriptionsOwn) {
  const MoveItProblem problem = arcplan::collision::loadMoveItProblem(
      problems() / "cage_ur5e" / "scene0001.yaml", problems() / "cage_ur5e" / "request0001.yaml", urType("ur5e"));
  const arcplan::collision::Scene& scene = problem.scene;
  EXPECT_EQ(scene.robot.urType, "ur5e");
  EXPECT_TRUE(scene.robot.urdf.empty());
  // The ball is given in base_link_inertia at (-0.4, -0.45, 0.45): turned by pi about z, (0.4, 0.45, 0.45).
  EXPECT_NEAR((named(scene, "ball").pose.translation() - Eigen::Vector3d(0.4, 0.45, 0.45)).norm(), 0.0, 1e-12);
  // The floor: fixed frame "cell" 0.02 m below the root, box centre 0.01 m below that.
  EXPECT_NEAR((named(scene, "floor").pose.translation() - Eigen::Vector3d(0, 0, -0.03)).norm(), 0.0, 1e-12);
  EXPECT_EQ(named(scene, "post").length, 1.0);  // [height, radius]
  EXPECT_EQ(named(scene, "post").radius, 0.05);
  EXPECT_EQ(named(scene, "wedge").shape, Obstacle::Shape::Mesh);
  ASSERT_EQ(scene.attachedObstacles.size(), 1u);
  EXPECT_EQ(scene.attachedObstacles[0].link, "tool0");
  // Every name the scene's pairs and attached bodies use is a link of the model UR's files make, or an object.
  const auto links = linkNamesOf(arcplan::robot::loadUrDescription({"ur5e", {}, {}}));
  const std::set<std::string> objects{"floor", "post", "ball", "wedge", "probe"};
  for (const auto& [a, b] : scene.allowedCollisions) {
    for (const auto& name : {a, b}) EXPECT_TRUE(links.count(name) + objects.count(name) == 1) << name;
  }
  const std::pair<std::string, std::string> probeWrist{"probe", "wrist_3_link"};
  EXPECT_NE(std::find(scene.allowedCollisions.begin(), scene.allowedCollisions.end(), probeWrist),
            scene.allowedCollisions.end());
  EXPECT_EQ(problem.startState.size(), 6u);
  EXPECT_EQ(problem.startState.count("shoulder_pan_joint"), 1u);
}

TEST(MoveItUrType, NamesNotInTheDescriptionAreErrorsNamingIt) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_ur_type_names");
  std::ofstream(dir / "gripper.yaml") << "robot_state:\n  joint_state:\n    name: [robotiq_85_left_knuckle_joint]\n"
                                         "    position: [0]\n";
  const std::string joint = arcplan::testing::errorMessageOf(
      [&] { arcplan::collision::loadMoveItScene(dir / "gripper.yaml", urType("ur5e")); });
  EXPECT_NE(joint.find("gripper.yaml:3:"), std::string::npos) << joint;
  EXPECT_NE(joint.find("'robotiq_85_left_knuckle_joint' is no joint of the robot 'ur5e'"), std::string::npos) << joint;
  std::ofstream(dir / "frame.yaml") << "world:\n  collision_objects:\n    - id: a\n      header: {frame_id: ee_link}\n"
                                       "      primitives: [{type: sphere, dimensions: [0.1]}]\n"
                                       "      primitive_poses: [{}]\n";
  const std::string frame = arcplan::testing::errorMessageOf(
      [&] { arcplan::collision::loadMoveItScene(dir / "frame.yaml", urType("ur5e")); });
  EXPECT_NE(frame.find("frame.yaml:4:"), std::string::npos) << frame;
  EXPECT_NE(frame.find("unknown frame 'ee_link'"), std::string::npos) << frame;
}

TEST(MoveItUrType, PlanTakesTheUrTypeOnTheMoveItPath) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_ur_type_plan");
  const auto json = dir / "plan.json";
  const auto result = arcplan::testing::runArcplan(
      {"plan", "--moveit-scene", (problems() / "cage_ur5e" / "scene0001.yaml").string(), "--moveit-request",
       (problems() / "cage_ur5e" / "request0001.yaml").string(), "--ur-type", "ur5e", "--planner", "RRTConnect",
       "--seed", "1", "--json", json.string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto document = nlohmann::json::parse(arcplan::testing::readFile(json));
  EXPECT_EQ(document["status"], "exact");
  EXPECT_EQ(document["start_valid"], true);
  EXPECT_EQ(document["goal_valid"], true);
  // --kinematics without --ur-type is still a usage error.
  EXPECT_EQ(
      arcplan::testing::runArcplan({"plan", "--moveit-scene", (problems() / "cage_ur5e" / "scene0001.yaml").string(),
                                    "--moveit-request", (problems() / "cage_ur5e" / "request0001.yaml").string(),
                                    "--urdf", arcplan::robot::ur10eUrdfPath().string(), "--kinematics", json.string()})
          .exitCode,
      2);
}

TEST(MoveItUrType, EveryFamilyOfASuiteLoadsValidAndPlans) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_ur_type_suite");
  std::ofstream(dir / "suite.yaml") << "name: families\nmoveit_problems: {folder: " << problems().string()
                                    << ", ur_type: ur5e}\nplanners: [RRTConnect]\n";
  const arcplan::benchmarks::Suite suite = arcplan::benchmarks::loadSuite(dir / "suite.yaml");
  ASSERT_EQ(suite.problems.size(), 2u);
  EXPECT_TRUE(suite.excludedProblems.empty());
  std::set<std::string> families;
  for (const auto& problem : suite.problems) {
    families.insert(problem.kind);
    EXPECT_EQ(problem.scene.robot.urType, "ur5e");
    for (const std::string planner : {"RRTConnect", "arc"}) {
      arcplan::benchmarks::PlanQueryOptions options;
      options.planner = planner;
      options.seed = 1;
      options.clearance = 0.01;
      const auto planned = arcplan::benchmarks::planQuery(
          std::make_shared<const arcplan::collision::Scene>(problem.scene), problem.query, options);
      EXPECT_EQ(planned.status, arcplan::benchmarks::PlanStatus::Exact) << problem.name << " " << planner;
      EXPECT_GE(planned.clearanceMargin, 0.0) << problem.name << " " << planner;
    }
  }
  EXPECT_EQ(families, (std::set<std::string>{"cage_ur5e", "shelf_pick_ur5e"}));
  // Both robots, or a calibration without a type: the entry's line and what it expects.
  std::ofstream(dir / "both.yaml") << "name: both\nmoveit_problems: {folder: " << problems().string()
                                   << ", ur_type: ur5e, urdf: " << arcplan::robot::ur10eUrdfPath().string()
                                   << "}\nplanners: [RRTConnect]\n";
  const std::string both = arcplan::testing::errorMessageOf([&] { arcplan::benchmarks::loadSuite(dir / "both.yaml"); });
  EXPECT_NE(both.find("both.yaml:2:"), std::string::npos) << both;
  EXPECT_NE(both.find("expected either 'urdf' or 'ur_type'"), std::string::npos) << both;
  std::ofstream(dir / "kinematics.yaml") << "name: k\nmoveit_problems: {folder: " << problems().string()
                                         << ", urdf: " << arcplan::robot::ur10eUrdfPath().string()
                                         << ", kinematics: " << (dir / "suite.yaml").string()
                                         << "}\nplanners: [RRTConnect]\n";
  EXPECT_NE(arcplan::testing::errorMessageOf([&] {
              arcplan::benchmarks::loadSuite(dir / "kinematics.yaml");
            }).find("'description' and 'kinematics' go with 'ur_type'"),
            std::string::npos);
}

// Every type in the description folder reads a MoveIt problem and plans it: the cage's request in a
// scene with only the floor (the cage is sized for the UR5e).
TEST(MoveItUrType, EveryDescriptionTypePlansAMoveItProblem) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_ur_types");
  std::ofstream(dir / "floor.yaml")
      << "world:\n  collision_objects:\n    - id: floor\n      primitives: [{type: box, "
         "dimensions: [3, 3, 0.02]}]\n      primitive_poses: [{position: [0, 0, -0.03]}]\n";
  const auto types = arcplan::robot::urTypesIn(arcplan::robot::defaultUrDescriptionFolder());
  ASSERT_GE(types.size(), 7u);
  for (const auto& type : types) {
    const MoveItProblem problem = arcplan::collision::loadMoveItProblem(
        dir / "floor.yaml", problems() / "cage_ur5e" / "request0001.yaml", urType(type));
    arcplan::benchmarks::PlanQueryOptions options;
    options.planner = "RRTConnect";
    options.seed = 1;
    const auto planned =
        arcplan::benchmarks::planQuery(std::make_shared<const arcplan::collision::Scene>(problem.scene), "", options);
    EXPECT_EQ(planned.status, arcplan::benchmarks::PlanStatus::Exact) << type << ": " << planned.reason;
  }
}

// A type the description folder does not have: the UR20, from its datasheet DH parameters (d1 0.2363,
// a2 -0.862, a3 -0.7287, d4 0.201, d5 0.1593, d6 0.1543 m), in a folder made at run time beside links
// of UR's UR10e limits, masses and meshes. Its tool0 must be the DH chain's last frame seen from
// base_link (UR's `base` frame, the DH base, is base_link turned by pi about z), IK must give the
// configurations back, and it must read and plan a MoveIt problem.
TEST(MoveItUrType, ATypeTheFolderDoesNotHaveLoadsMatchesItsDhAndPlans) {
  const auto dir = arcplan::testing::freshTempDirectory("moveit_ur20");
  const fs::path shared = arcplan::robot::defaultUrDescriptionFolder();
  fs::create_directories(dir / "config" / "ur20");
  fs::create_directory_symlink(shared / "meshes", dir / "meshes");
  for (const char* file : {"joint_limits.yaml", "physical_parameters.yaml", "visual_parameters.yaml"})
    fs::create_symlink(shared / "config" / "ur10e" / file, dir / "config" / "ur20" / file);
  const double d1 = 0.2363, a2 = -0.862, a3 = -0.7287, d4 = 0.201, d5 = 0.1593, d6 = 0.1543;
  std::ofstream(dir / "config" / "ur20" / "default_kinematics.yaml")
      << "kinematics:\n"
      << "  shoulder: {x: 0, y: 0, z: " << d1 << ", roll: 0, pitch: 0, yaw: 0}\n"
      << "  upper_arm: {x: 0, y: 0, z: 0, roll: 1.5707963267948966, pitch: 0, yaw: 0}\n"
      << "  forearm: {x: " << a2 << ", y: 0, z: 0, roll: 0, pitch: 0, yaw: 0}\n"
      << "  wrist_1: {x: " << a3 << ", y: 0, z: " << d4 << ", roll: 0, pitch: 0, yaw: 0}\n"
      << "  wrist_2: {x: 0, y: " << -d5 << ", z: 0, roll: 1.5707963267948966, pitch: 0, yaw: 0}\n"
      << "  wrist_3: {x: 0, y: " << d6
      << ", z: 0, roll: 1.5707963267948966, pitch: 3.141592653589793, yaw: 3.141592653589793}\n";
  const arcplan::robot::RobotModel model = arcplan::robot::loadUrDescription({"ur20", dir, {}});
  const arcplan::robot::UrInverseKinematics ik(model);
  arcplan::robot::KinematicsData data(model);
  std::mt19937 random(20);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  const double d[] = {d1, 0, 0, d4, d5, d6}, a[] = {0, a2, a3, 0, 0, 0};
  const double alpha[] = {M_PI_2, 0, 0, M_PI_2, -M_PI_2, 0};
  for (int trial = 0; trial < 50; ++trial) {
    arcplan::robot::Vector6 q;
    for (int j = 0; j < 6; ++j) q[j] = angle(random);
    Eigen::Isometry3d expected(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
    for (int j = 0; j < 6; ++j) {
      expected = expected * Eigen::AngleAxisd(q[j], Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(a[j], 0, d[j]) *
                 Eigen::AngleAxisd(alpha[j], Eigen::Vector3d::UnitX());
    }
    arcplan::robot::forwardKinematics(model, q, data);
    EXPECT_LT((data.linkPoses[model.linkIndex("tool0")].matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-9);
    double closest = 1e9;
    for (const auto& solution : ik.solveBranches(expected)) {
      double worst = 0.0;
      for (int j = 0; j < 6; ++j) worst = std::max(worst, std::abs(std::remainder(solution[j] - q[j], 2 * M_PI)));
      closest = std::min(closest, worst);
    }
    EXPECT_LT(closest, 1e-9) << q.transpose();
  }
  // The cage's request in a scene with only a floor, read against the UR20's names.
  std::ofstream(dir / "floor.yaml")
      << "world:\n  collision_objects:\n    - id: floor\n      primitives: [{type: box, "
         "dimensions: [4, 4, 0.02]}]\n      primitive_poses: [{position: [0, 0, -0.03]}]\n";
  const MoveItProblem problem = arcplan::collision::loadMoveItProblem(
      dir / "floor.yaml", problems() / "cage_ur5e" / "request0001.yaml", {{}, {}, {"ur20", dir, {}}});
  EXPECT_EQ(problem.scene.robot.urType, "ur20");
  arcplan::benchmarks::PlanQueryOptions options;
  options.planner = "RRTConnect";
  options.seed = 1;
  const auto planned =
      arcplan::benchmarks::planQuery(std::make_shared<const arcplan::collision::Scene>(problem.scene), "", options);
  EXPECT_EQ(planned.status, arcplan::benchmarks::PlanStatus::Exact) << planned.reason;

  // The readers cache the description by its files' contents: the calibration rewritten in place (d1 one
  // centimetre longer, same size and time) moves a ball held at tool0 one centimetre up.
  std::ofstream(dir / "held.yaml") << "world:\n  collision_objects:\n    - id: ball\n      header: {frame_id: tool0}\n"
                                      "      primitives: [{type: sphere, dimensions: [0.05]}]\n"
                                      "      primitive_poses: [{}]\n";
  const MoveItRobot ur20{{}, {}, {"ur20", dir, {}}};
  const double before =
      arcplan::collision::loadMoveItScene(dir / "held.yaml", ur20).scene.obstacles[0].pose.translation().z();
  const auto kinematics = dir / "config" / "ur20" / "default_kinematics.yaml";
  const auto written = fs::last_write_time(kinematics);
  std::string text = arcplan::testing::readFile(kinematics);
  text.replace(text.find("0.2363"), 6, "0.2463");
  std::ofstream(kinematics) << text;
  fs::last_write_time(kinematics, written);
  const double after =
      arcplan::collision::loadMoveItScene(dir / "held.yaml", ur20).scene.obstacles[0].pose.translation().z();
  EXPECT_NEAR(after - before, 0.01, 1e-12);
}

}  // namespace
