// `arcplan robot check` end to end: results as text and JSON, and every bad-input error as one
// line on stderr with a non-zero exit code and no JSON file left behind.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/command.h"

namespace {

using arcplan::testing::freshTempDirectory;
using arcplan::testing::readFile;
using arcplan::testing::runArcplan;

const std::string kSolutionA = "-1.098,-1.510,2.351,-2.411,-1.571,-1.098";
const std::string kFolded = "0,-1.5707963,3.1415926,0,1.5707963,0";

std::string thesisScene() { return std::string(ARCPLAN_TEST_DATA_DIR) + "/scenes/thesis_obstacle.yaml"; }

TEST(RobotCheckCommand, ThesisSolutionIsValidWithPositiveClearance) {
  const auto dir = freshTempDirectory("check_valid");
  const auto result = runArcplan(
      {"robot", "check", "--scene", thesisScene(), "--joints=" + kSolutionA, "--json", (dir / "check.json").string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("valid         yes"), std::string::npos) << result.out;
  const auto json = nlohmann::json::parse(readFile(dir / "check.json"));
  EXPECT_TRUE(json.at("valid").get<bool>());
  EXPECT_TRUE(json.at("collisions").empty());
  EXPECT_GT(json.at("clearance_m").get<double>(), 0.0);
  // The clearance the state meets: its closest self pair (forearm – wrist 3, ~7 cm) is nearer than the table, but
  // a clearance asks at most 1 mm of the robot's own links (docs/collision.md#clearance): the obstacle distance.
  ASSERT_LT(json.at("self_distance_m").get<double>(), json.at("obstacle_distance_m").get<double>());
  ASSERT_GT(json.at("self_distance_m").get<double>(), 0.001);
  EXPECT_EQ(json.at("clearance_m").get<double>(), json.at("obstacle_distance_m").get<double>());
  EXPECT_EQ(json.at("scene"), "thesis_obstacle");
}

TEST(RobotCheckCommand, FoldedArmReportsItsCollidingPairs) {
  const auto result =
      runArcplan({"robot", "check", "--scene", "scenes/thesis_free.yaml", "--joints=" + kFolded, "--json", "-"});
  ASSERT_EQ(result.exitCode, 0) << result.err;  // a collision is a result, not an error
  const auto json = nlohmann::json::parse(result.out.substr(result.out.find('{')));
  EXPECT_FALSE(json.at("valid").get<bool>());
  EXPECT_EQ(json.at("clearance_m").get<double>(), 0.0);
  bool wristOnUpperArm = false;
  for (const auto& pair : json.at("collisions"))
    wristOnUpperArm |= pair == nlohmann::json{"upper_arm_link", "wrist_1_link"};
  EXPECT_TRUE(wristOnUpperArm) << json.dump();
}

TEST(RobotCheckCommand, QueryChecksStartAndGoal) {
  const auto result = runArcplan({"robot", "check", "--scene", thesisScene(), "--query", "A_to_B", "--json", "-"});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto json = nlohmann::json::parse(result.out.substr(result.out.find('{')));
  EXPECT_TRUE(json.at("start").at("valid").get<bool>());
  EXPECT_TRUE(json.at("goal").at("valid").get<bool>());
  // The start is the elbow-up solution of A named in the issue.
  EXPECT_NEAR(json.at("start").at("joints")[0].get<double>(), -1.098, 1e-3);
  EXPECT_NEAR(json.at("start").at("joints")[2].get<double>(), 2.351, 1e-3);
}

struct BadInput {
  std::string name, sceneText, extraArgument, expectedMessage;
  int exitCode = 1;  // docs/cli.md: 1 for a scene arcplan cannot use, 2 for a wrong command line
};

TEST(RobotCheckCommand, BadInputGivesOneClearLineAndNoOutputFile) {
  const std::string header = "name: bad\nrobot: ur10e\n";
  const std::vector<BadInput> cases{
      {"malformed", header + "obstacles:\n  - name: a\n   sphere: {radius: 1}\n", "", "malformed YAML"},
      {"shape", header + "obstacles:\n  - {name: a, cone: {radius: 1}, position: [0, 0, 0]}\n", "",
       "obstacles[0]: unknown key 'cone'"},
      {"radius", header + "obstacles:\n  - {name: a, sphere: {}, position: [0, 0, 0]}\n", "",
       "obstacles[0] ('a').sphere: missing 'radius'"},
      {"negative", header + "obstacles:\n  - {name: a, box: {size: [1, 1, -1]}, position: [0, 0, 0]}\n", "",
       "box.size[2]: expected a positive number"},
      {"length", header + "obstacles:\n  - {name: a, sphere: {radius: 1}, position: [0, 0, 0, 0]}\n", "",
       "position: expected a list of 3 numbers, got 4"},
      {"mesh", header + "obstacles:\n  - {name: a, mesh: {file: no_such.stl}, position: [0, 0, 0]}\n", "",
       "mesh.file:"},
      {"link", header + "allowed_collisions:\n  - [table, wrist_7_link]\n", "", "unknown link or obstacle 'table'"},
      {"query", header, "--query=Z", "has no queries"},
      {"joints", header, "--joints=1,2,3", "--joints", 2},
      {"limits", header, "--joints=0,0,4,0,0,0", "outside its limits", 2},
  };
  for (const auto& bad : cases) {
    const auto dir = freshTempDirectory("check_bad_" + bad.name);
    const auto sceneFile = dir / "scene.yaml";
    std::ofstream(sceneFile) << bad.sceneText;
    const auto jsonFile = dir / "out.json";
    const std::string selection = bad.extraArgument.empty() ? "--joints=" + kSolutionA : bad.extraArgument;
    const auto result =
        runArcplan({"robot", "check", "--scene", sceneFile.string(), selection, "--json", jsonFile.string()});
    EXPECT_EQ(result.exitCode, bad.exitCode) << bad.name << ": " << result.err;
    EXPECT_EQ(result.out, "") << bad.name << ": nothing is printed before the inputs are checked";
    EXPECT_EQ(result.err.rfind("arcplan: error: ", 0), 0u) << bad.name << ": " << result.err;
    EXPECT_NE(result.err.find(bad.expectedMessage), std::string::npos) << bad.name << ": " << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << bad.name << ": " << result.err;
    EXPECT_FALSE(std::filesystem::exists(jsonFile)) << bad.name;
  }
}

TEST(RobotCheckCommand, MalformedYamlNamesTheLine) {
  const auto dir = freshTempDirectory("check_line");
  std::ofstream(dir / "scene.yaml") << "name: bad\nobstacles:\n  - name: a\n   sphere: {radius: 1}\n";
  const auto result =
      runArcplan({"robot", "check", "--scene", (dir / "scene.yaml").string(), "--joints=" + kSolutionA});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find("scene.yaml:4:"), std::string::npos) << result.err;  // the badly indented line
}

TEST(RobotCheckCommand, UnknownSceneFileAndUnknownQuery) {
  const auto missing = runArcplan({"robot", "check", "--scene", "/nonexistent/s.yaml", "--joints=" + kSolutionA});
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.err.find("scene file /nonexistent/s.yaml does not exist"), std::string::npos) << missing.err;
  const auto query = runArcplan({"robot", "check", "--scene", thesisScene(), "--query", "B_to_A"});
  EXPECT_EQ(query.exitCode, 1);
  EXPECT_NE(query.err.find("has no query 'B_to_A'; queries: A_to_B"), std::string::npos) << query.err;
  const auto both =
      runArcplan({"robot", "check", "--scene", thesisScene(), "--query", "A_to_B", "--joints=" + kSolutionA});
  EXPECT_EQ(both.exitCode, 2);
  EXPECT_NE(both.err.find("exactly one of --joints or --query"), std::string::npos) << both.err;
}

}  // namespace
