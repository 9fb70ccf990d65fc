// UR arms from other people's files (../shared/data): MotionBenchMaker's UR5 with its force sensor and
// gripper, and every type of Universal Robots' own description. Expected numbers come from UR's
// published DH tables and from the description's YAML composed here by hand, never from the code
// under test.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_description.h"
#include "arcplan/robot/ur_inverse_kinematics.h"
#include "support/command.h"
#include "robot/ur_round_trips.h"
#include "support/joint_states.h"

namespace {

using arcplan::robot::RobotModel;
using arcplan::robot::UrInverseKinematics;
using arcplan::robot::Vector6;
using arcplan::testing::randomJointState;

std::filesystem::path mbmUr5Urdf() { return arcplan::testing::sharedDataDirectory() / "mbm_ur5" / "ur5.urdf"; }

// Random configurations -> tip pose -> IK: how many of the configurations are among the solutions (to
// 1e-9), every solution reproducing the pose to 1e-9.
int roundTrips(const RobotModel& model, unsigned seed, int trials) {
  return arcplan::testing::urRoundTrips(model, seed, trials, 1e-9);
}

void expectRoundTrips(const RobotModel& model, unsigned seed, int trials) {
  EXPECT_EQ(roundTrips(model, seed, trials), trials) << model.name();
}

TEST(MotionBenchMakerUr5, LoadsWithItsSensorAndGripperAsCollisionBodies) {
  const RobotModel model = arcplan::robot::loadRobotModel(mbmUr5Urdf());
  EXPECT_EQ(model.name(), "ur5_robotiq85");
  EXPECT_EQ(model.dof(), 6);
  for (const char* name : {"fts_robotside", "robotiq_85_base_link", "robotiq_85_left_finger_tip_link",
                           "robotiq_85_right_finger_tip_link", "robotiq_85_left_knuckle_link"}) {
    const auto& link = model.links()[model.linkIndex(name)];
    EXPECT_FALSE(link.collisions.empty()) << name;
    EXPECT_EQ(link.joint, -1) << name;  // moves with the flange
  }
}

TEST(MotionBenchMakerUr5, DhParametersAreTheUr5Ones) {
  // UR's published DH table of the UR5 (CB-series): d1, a2, a3, d4, d5, d6.
  const UrInverseKinematics ik(arcplan::robot::loadRobotModel(mbmUr5Urdf()));
  const auto& dh = ik.dhParameters();
  EXPECT_NEAR(dh.d1, 0.089159, 1e-6);
  EXPECT_NEAR(dh.a2, -0.425, 1e-6);
  EXPECT_NEAR(dh.a3, -0.39225, 1e-6);
  EXPECT_NEAR(dh.d4, 0.10915, 1e-6);
  EXPECT_NEAR(dh.d5, 0.09465, 1e-6);
  EXPECT_NEAR(dh.d6, 0.0823, 1e-6);
  // Its pi/2 is written 1.570796325: not an exact UR chain, within the URDF tolerance.
  EXPECT_GT(ik.translationDeviation() + ik.rotationDeviation(), 1e-10);
  EXPECT_LT(std::max(ik.translationDeviation(), ik.rotationDeviation()), arcplan::robot::kUrdfChainTolerance);
}

TEST(MotionBenchMakerUr5, InverseKinematicsRoundTripsToOneNanometre) {
  expectRoundTrips(arcplan::robot::loadRobotModel(mbmUr5Urdf()), 11, 500);
}

TEST(MotionBenchMakerUr5, ToolFrameInTheGripperRoundTrips) {
  // The TCP between the finger tips, a link beyond the flange that only fixed joints reach.
  expectRoundTrips(
      arcplan::robot::loadRobotModel(mbmUr5Urdf(), {"base_link", "robotiq_85_left_finger_tip_link", std::nullopt}), 12,
      200);
}

// Three of this UR5's joints turn about y: every link's pose is compared with the product of its origins and the
// axis-angle rotations of its joints, composed here link by link (to 1e-12); the tip chain alone (chainKinematics)
// gives the tip and its ancestors exactly those of the whole model.
TEST(MotionBenchMakerUr5, LinkPosesAreTheProductsOfOriginsAndAxisAngleRotations) {
  const RobotModel model = arcplan::robot::loadRobotModel(mbmUr5Urdf());
  const auto& links = model.links();
  const bool turnsAboutY = std::any_of(links.begin(), links.end(), [](const arcplan::robot::Link& link) {
    return link.joint >= 0 && link.axis == Eigen::Vector3d::UnitY();
  });
  ASSERT_TRUE(turnsAboutY) << "the test needs joints about another axis than z";
  std::mt19937 random(3);
  arcplan::robot::KinematicsData whole(model), chain(model);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::VectorXd q = randomJointState(model, random);
    arcplan::robot::forwardKinematics(model, q, whole);
    std::vector<Eigen::Isometry3d> expected(links.size());
    for (std::size_t i = 0; i < links.size(); ++i) {
      const arcplan::robot::Link& link = links[i];
      expected[i] = link.parent < 0 ? link.originInParent : expected[link.parent] * link.originInParent;
      if (link.joint >= 0) expected[i] = expected[i] * Eigen::AngleAxisd(q[link.joint], link.axis);
      EXPECT_TRUE(whole.linkPoses[i].isApprox(expected[i], 1e-12)) << link.name << " trial " << trial;
    }
    arcplan::robot::chainKinematics(model, q, model.tipLink(), chain);
    for (int l = model.tipLink(); l >= 0; l = links[l].parent)
      EXPECT_TRUE(chain.linkPoses[l].matrix() == whole.linkPoses[l].matrix()) << links[l].name;
  }
}

}  // namespace

namespace {

using arcplan::robot::loadUrDescription;
using arcplan::robot::UrDescriptionSelection;

std::filesystem::path descriptionFolder() { return arcplan::testing::sharedDataDirectory() / "ur_description"; }

// Every type the folder holds, listed here from the folder itself.
std::vector<std::string> typesInFolder() {
  std::vector<std::string> types;
  for (const auto& entry : std::filesystem::directory_iterator(descriptionFolder() / "config")) {
    if (entry.is_directory()) types.push_back(entry.path().filename().string());
  }
  std::sort(types.begin(), types.end());
  return types;
}

Eigen::Isometry3d xyzRpy(const Eigen::Vector3d& xyz, double roll, double pitch, double yaw) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = xyz;
  t.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return t;
}

// The joint frames of a default_kinematics.yaml composed by hand, as UR's xacro macro chains them:
// base_link -> base_link_inertia (pi about z) -> each joint's x, y, z, roll, pitch, yaw, then the
// joint turning about its z; the tool0 frame after the flange's two fixed turns.
std::vector<Eigen::Isometry3d> framesFromYaml(const std::filesystem::path& kinematicsFile, const Vector6& q) {
  const YAML::Node kinematics = YAML::LoadFile(kinematicsFile.string())["kinematics"];
  std::vector<Eigen::Isometry3d> frames;
  Eigen::Isometry3d pose = xyzRpy(Eigen::Vector3d::Zero(), 0, 0, M_PI);
  int j = 0;
  for (const char* name : {"shoulder", "upper_arm", "forearm", "wrist_1", "wrist_2", "wrist_3"}) {
    const YAML::Node f = kinematics[name];
    pose = pose *
           xyzRpy({f["x"].as<double>(), f["y"].as<double>(), f["z"].as<double>()}, f["roll"].as<double>(),
                  f["pitch"].as<double>(), f["yaw"].as<double>()) *
           xyzRpy(Eigen::Vector3d::Zero(), 0, 0, q[j++]);
    frames.push_back(pose);
  }
  frames.push_back(pose * xyzRpy(Eigen::Vector3d::Zero(), 0, -M_PI_2, -M_PI_2) *
                   xyzRpy(Eigen::Vector3d::Zero(), M_PI_2, 0, M_PI_2));
  return frames;
}

void expectFramesMatchYaml(const RobotModel& model, const std::filesystem::path& kinematicsFile, unsigned seed) {
  const char* links[] = {"shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link",
                         "wrist_2_link",  "wrist_3_link",   "tool0"};
  arcplan::robot::KinematicsData data(model);
  std::mt19937 random(seed);
  for (int trial = 0; trial < 50; ++trial) {
    const Vector6 q = randomJointState(model, random);
    arcplan::robot::forwardKinematics(model, q, data);
    const auto expected = framesFromYaml(kinematicsFile, q);
    for (int k = 0; k < 7; ++k) {
      const auto& actual = data.linkPoses[model.linkIndex(links[k])];
      EXPECT_LT((actual.matrix() - expected[k].matrix()).cwiseAbs().maxCoeff(), 1e-12)
          << model.name() << " " << links[k];
    }
  }
}

TEST(UrDescription, EveryTypeMatchesItsDefaultKinematicsFrames) {
  const auto types = typesInFolder();
  ASSERT_GE(types.size(), 7u);
  for (const auto& type : types) {
    const RobotModel model = loadUrDescription({type, descriptionFolder(), {}});
    EXPECT_EQ(model.name(), type);
    EXPECT_FALSE(model.calibrated());
    expectFramesMatchYaml(model, descriptionFolder() / "config" / type / "default_kinematics.yaml", 21);
  }
}

TEST(UrDescription, EveryTypeRoundTripsToOneNanometre) {
  for (const auto& type : typesInFolder())
    expectRoundTrips(loadUrDescription({type, descriptionFolder(), {}}), 22, 300);
}

TEST(UrDescription, LinksCarryTheMassesAndCollisionMeshesOfTheirFiles) {
  const RobotModel model = loadUrDescription({"ur16e", descriptionFolder(), {}});
  const YAML::Node inertia =
      YAML::LoadFile((descriptionFolder() / "config/ur16e/physical_parameters.yaml").string())["inertia_parameters"];
  for (const char* name : {"shoulder", "upper_arm", "forearm", "wrist_1", "wrist_2", "wrist_3"}) {
    const auto& link = model.links()[model.linkIndex(std::string(name) + "_link")];
    EXPECT_DOUBLE_EQ(link.inertial.mass, inertia[std::string(name) + "_mass"].as<double>()) << name;
    ASSERT_EQ(link.collisions.size(), 1u) << name;
  }
  // The UR16e reuses UR10e parts except the two arm tubes (its visual_parameters.yaml).
  const auto meshOf = [&](const char* link) { return model.links()[model.linkIndex(link)].collisions[0].meshFile; };
  EXPECT_EQ(meshOf("wrist_1_link"), descriptionFolder() / "meshes/ur10e/collision/wrist1.stl");
  EXPECT_EQ(meshOf("upper_arm_link"), descriptionFolder() / "meshes/ur16e/collision/upperarm.stl");
  EXPECT_EQ(meshOf("base_link_inertia"), descriptionFolder() / "meshes/ur10e/collision/base.stl");
  // joint_limits.yaml gives the elbow +-180 degrees.
  EXPECT_NEAR(model.joints()[2].limits.upper, M_PI, 1e-12);
}

// The default folder (../shared/data/ur_description) is relative to the current directory: its meshes must
// be the files under that folder, not a path read relative to the kinematics file's own folder.
TEST(UrDescription, RelativeFolderNamesMeshesUnderItself) {
  const std::filesystem::path absolute = std::filesystem::absolute(descriptionFolder());
  const std::filesystem::path relative = std::filesystem::relative(absolute);
  ASSERT_TRUE(relative.is_relative());
  const RobotModel model = loadUrDescription({"ur5e", relative, {}});
  for (const char* name : {"shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link"}) {
    const auto& link = model.links()[model.linkIndex(name)];
    ASSERT_EQ(link.collisions.size(), 1u) << name;
    EXPECT_TRUE(std::filesystem::is_regular_file(link.collisions[0].meshFile)) << link.collisions[0].meshFile;
    EXPECT_TRUE(
        std::filesystem::equivalent(link.collisions[0].meshFile.parent_path(), absolute / "meshes/ur5e/collision"))
        << link.collisions[0].meshFile;
  }
}

// A factory calibration: every joint frame moved by up to 1 mm and 1 mrad from the nominal one.
std::filesystem::path writeCalibration(const std::string& type, unsigned seed) {
  YAML::Node root = YAML::LoadFile((descriptionFolder() / "config" / type / "default_kinematics.yaml").string());
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-0.001, 0.001);
  for (auto entry : root["kinematics"]) {
    if (!entry.second.IsMap()) continue;
    for (const char* key : {"x", "y", "z", "roll", "pitch", "yaw"}) {
      entry.second[key] = entry.second[key].as<double>() + offset(random);
    }
  }
  const auto file = arcplan::testing::freshTempDirectory("calibration_" + type) / "my_calibration.yaml";
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << root;
  std::ofstream(file) << out.c_str();
  return file;
}

TEST(UrDescription, CalibratedArmPlansWithItsTrueGeometry) {
  for (const std::string type : {"ur5e", "ur10"}) {
    const auto calibration = writeCalibration(type, 5);
    const RobotModel model = loadUrDescription({type, descriptionFolder(), calibration});
    EXPECT_TRUE(model.calibrated());
    expectFramesMatchYaml(model, calibration, 23);
    const UrInverseKinematics ik(model);
    // Millimetre offsets: far beyond what a URDF may carry, so the Newton refinement is what is tested.
    EXPECT_GT(ik.translationDeviation(), 1e-4);
    // Every solution is exact; a configuration within the calibration's deviation of a point where two
    // branches merge (elbow stretched, wrist 2 at 0 or pi) may come back on the neighbouring branch.
    EXPECT_GE(roundTrips(model, 24, 500), 490) << type;
  }
}

TEST(UrDescription, UnknownTypeListsTheKnownOnes) {
  try {
    loadUrDescription({"ur7e", descriptionFolder(), {}});
    FAIL() << "no error";
  } catch (const arcplan::Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown UR type 'ur7e'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ur10e, ur16e, ur3"), std::string::npos) << e.what();
  }
}

TEST(UrDescription, MissingFieldInACalibrationNamesFileLineAndField) {
  const auto dir = arcplan::testing::freshTempDirectory("calibration_missing");
  std::string text = arcplan::testing::readFile(descriptionFolder() / "config/ur5e/default_kinematics.yaml");
  // Drop the yaw of wrist_2 (the 5th "yaw:" line of the file).
  std::size_t at = 0;
  for (int k = 0; k < 5; ++k) at = text.find("yaw:", at + 1);
  text.erase(at, text.find('\n', at) - at);
  std::ofstream(dir / "k.yaml") << text;
  try {
    loadUrDescription({"ur5e", descriptionFolder(), dir / "k.yaml"});
    FAIL() << "no error";
  } catch (const arcplan::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find((dir / "k.yaml").string() + ":"), std::string::npos) << message;
    EXPECT_NE(message.find("kinematics.wrist_2: missing 'yaw'"), std::string::npos) << message;
  }
}

}  // namespace

// The command line and scenes on these robots, through the real `arcplan` binary.
namespace {

using arcplan::testing::runArcplan;

std::filesystem::path writeScene(const std::string& name, const std::string& robot, const std::string& rest = "") {
  const auto file = arcplan::testing::freshTempDirectory("scene_" + name) / "scene.yaml";
  std::ofstream(file) << "name: " << name << "\nrobot: " << robot << "\n" << rest;
  return file;
}

const char* kJointQuery = R"(obstacles:
  - name: post
    cylinder: {radius: 0.05, length: 2.0}
    position: [1.5, 1.5, 0.0]
queries:
  - name: swing
    start: {joints: [0, -1.57, 1.0, -1.0, -1.57, 0]}
    goal: {joints: [1.2, -1.2, 1.3, -1.6, -1.57, 0.6]}
)";

TEST(UrArmsOnTheCommandLine, EveryDescriptionTypePlansFromAScene) {
  for (const auto& type : typesInFolder()) {
    const auto scene = writeScene("plan_" + type, "{ur_type: " + type + "}", kJointQuery);
    const auto json = scene.parent_path() / "plan.json";
    const auto result = runArcplan({"plan", "--scene", scene.string(), "--planner", "RRTConnect", "--time", "5",
                                    "--seed", "1", "--json", json.string()});
    ASSERT_EQ(result.exitCode, 0) << type << ": " << result.err;
    EXPECT_EQ(nlohmann::json::parse(arcplan::testing::readFile(json))["status"], "exact") << type;
  }
}

TEST(UrArmsOnTheCommandLine, MotionBenchMakerUr5PlansWithItsSrdf) {
  const auto scene = writeScene(
      "plan_mbm",
      "{urdf: " + mbmUr5Urdf().string() + ", srdf: " + (mbmUr5Urdf().parent_path() / "ur5.srdf").string() + "}",
      kJointQuery);
  const auto json = scene.parent_path() / "plan.json";
  const auto result = runArcplan({"plan", "--scene", scene.string(), "--planner", "RRTConnect", "--time", "5", "--seed",
                                  "1", "--json", json.string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(nlohmann::json::parse(arcplan::testing::readFile(json))["status"], "exact");
}

TEST(UrArmsOnTheCommandLine, GripperFingersCollideWhereTheyAre) {
  // A small box where the left finger tip of the MBM UR5 is at this configuration: the finger (a link
  // beyond the flange that only fixed joints reach) is what touches it.
  const RobotModel model = arcplan::robot::loadRobotModel(mbmUr5Urdf());
  Vector6 q;
  q << 0.3, -1.2, 1.4, -1.8, -1.57, 0.2;
  arcplan::robot::KinematicsData data(model);
  arcplan::robot::forwardKinematics(model, q, data);
  const Eigen::Vector3d finger = data.linkPoses[model.linkIndex("robotiq_85_left_finger_tip_link")].translation();
  std::ostringstream obstacle;
  obstacle.precision(17);
  obstacle << "obstacles:\n  - name: crumb\n    sphere: {radius: 0.004}\n    position: [" << finger.x() << ", "
           << finger.y() << ", " << finger.z() << "]\n";
  const auto scene = writeScene("finger", "{urdf: " + mbmUr5Urdf().string() + "}", obstacle.str());
  const auto json = scene.parent_path() / "check.json";
  const auto result = runArcplan({"robot", "check", "--scene", scene.string(), "--joints",
                                  "0.3,-1.2,1.4,-1.8,-1.57,0.2", "--json", json.string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto document = nlohmann::json::parse(arcplan::testing::readFile(json));
  EXPECT_FALSE(document["valid"].get<bool>());
  bool fingerHit = false;
  for (const auto& pair : document["collisions"]) {
    fingerHit |= pair[0] == "robotiq_85_left_finger_tip_link" && pair[1] == "crumb";
  }
  EXPECT_TRUE(fingerHit) << document["collisions"].dump();
}

TEST(UrArmsOnTheCommandLine, ForwardKinematicsOfATypeMatchesItsYaml) {
  Vector6 q;
  q << 0.2, -1.1, 1.3, -0.7, 1.2, 0.4;
  const auto json = arcplan::testing::freshTempDirectory("fk_ur3e") / "fk.json";
  const auto result = runArcplan({"robot", "fk", "--ur-type", "ur3e", "--description", descriptionFolder().string(),
                                  "--joints", "0.2,-1.1,1.3,-0.7,1.2,0.4", "--json", json.string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto document = nlohmann::json::parse(arcplan::testing::readFile(json));
  const Eigen::Isometry3d tool0 = framesFromYaml(descriptionFolder() / "config/ur3e/default_kinematics.yaml", q).back();
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(document["position"][k].get<double>(), tool0.translation()[k], 1e-12);
  EXPECT_EQ(document["link"], "tool0");
}

TEST(UrArmsOnTheCommandLine, BadRobotInputSaysWhatAndWhere) {
  const auto unknown = writeScene("unknown_type", "{ur_type: ur7e}", kJointQuery);
  auto result = runArcplan({"robot", "check", "--scene", unknown.string(), "--joints", "0,-1.57,1,-1,-1.57,0"});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find(unknown.string() + ":2:"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("unknown UR type 'ur7e'"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("ur10e, ur16e"), std::string::npos) << result.err;

  const auto dir = arcplan::testing::freshTempDirectory("bad_srdf");
  std::ofstream(dir / "r.srdf")
      << "<robot name=\"r\">\n<disable_collisions link1=\"base_link\" link2=\"gripper\"/>\n</robot>\n";
  const auto badSrdf = writeScene("bad_srdf", "{ur_type: ur5e, srdf: " + (dir / "r.srdf").string() + "}", kJointQuery);
  result = runArcplan({"robot", "check", "--scene", badSrdf.string(), "--joints", "0,-1.57,1,-1,-1.57,0"});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find((dir / "r.srdf").string() + ":2: link 'gripper' is not a link of robot 'ur5e'"),
            std::string::npos)
      << result.err;

  result = runArcplan({"robot", "fk", "--joints", "0,0,0,0,0,0", "--kinematics", (dir / "r.srdf").string()});
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_NE(result.err.find("--description and --kinematics need --ur-type"), std::string::npos) << result.err;
}

}  // namespace
