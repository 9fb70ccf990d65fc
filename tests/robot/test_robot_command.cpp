#include <fstream>
#include <ostream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/command.h"

namespace {

using arcplan::testing::runArcplan;

TEST(RobotCommand, ForwardKinematicsPrintsAndWritesJson) {
  const auto dir = arcplan::testing::freshTempDirectory("fk_json");
  const auto result = runArcplan({"robot", "fk", "--joints", "0,0,0,0,0,0", "--json", (dir / "fk.json").string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("1.184250"), std::string::npos) << result.out;
  const auto json = nlohmann::json::parse(arcplan::testing::readFile(dir / "fk.json"));
  EXPECT_NEAR(json["position"][0].get<double>(), 1.18425, 1e-9);
  EXPECT_NEAR(json["position"][1].get<double>(), 0.29070, 1e-9);
  EXPECT_NEAR(json["position"][2].get<double>(), 0.06085, 1e-9);
  EXPECT_NEAR(json["rotation"][1][2].get<double>(), 1.0, 1e-12);  // tool0 y = base z at q = 0
}

TEST(RobotCommand, InverseKinematicsListsSolutionsAndNearest) {
  const auto dir = arcplan::testing::freshTempDirectory("ik_json");
  const auto result = runArcplan({"robot", "ik", "--pose", "0.4,-0.4,0.25,0,-3.141592653589793,1.5707963267948966",
                                  "--seed=-1.1,-1.5,2.35,-2.4,-1.57,-1.1", "--json", (dir / "ik.json").string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto json = nlohmann::json::parse(arcplan::testing::readFile(dir / "ik.json"));
  EXPECT_EQ(json["solutions"].size(), 256u);
  const std::vector<double> expected{-1.098, -1.510, 2.351, -2.411, -1.571, -1.098};
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(json["nearest"][j].get<double>(), expected[j], 1e-3);
}

struct BadInput {
  std::string name;  // of the test case
  std::vector<std::string> arguments;
  std::string expectedMessage;
  int exitCode;  // docs/cli.md: 2 for a wrong command line, 1 for input arcplan cannot use
};

// Names the case in test listings (gtest would dump the struct's bytes).
void PrintTo(const BadInput& input, std::ostream* out) { *out << input.name; }

class RobotCommandBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(RobotCommandBadInput, OneClearLineAndNonZeroExit) {
  const auto dir = arcplan::testing::freshTempDirectory("robot_bad_input");
  auto arguments = GetParam().arguments;
  arguments.push_back("--json");
  arguments.push_back((dir / "out.json").string());
  const auto result = runArcplan(arguments);
  EXPECT_EQ(result.exitCode, GetParam().exitCode) << result.err;
  EXPECT_NE(result.err.find(GetParam().expectedMessage), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.json")) << "output written despite the error";
  EXPECT_TRUE(std::filesystem::is_empty(dir)) << "temporary file left behind";
}

INSTANTIATE_TEST_SUITE_P(
    Errors, RobotCommandBadInput,
    ::testing::Values(
        BadInput{
            "FiveJoints", {"robot", "fk", "--joints", "0,0,0,0,0"}, "expected 6 comma-separated numbers, got 5", 2},
        BadInput{"NotANumber", {"robot", "fk", "--joints", "0,0,zero,0,0,0"}, "'zero' is not a finite number", 2},
        BadInput{"OutsideLimits", {"robot", "fk", "--joints", "0,0,4,0,0,0"}, "outside its limits", 2},
        BadInput{"MissingUrdf",
                 {"robot", "fk", "--joints", "0,0,0,0,0,0", "--urdf", "/nonexistent/robot.urdf"},
                 "/nonexistent/robot.urdf does not exist",
                 1},
        BadInput{
            "UnknownTip", {"robot", "fk", "--joints", "0,0,0,0,0,0", "--tip", "gripper"}, "'gripper' not found", 1},
        BadInput{"OutOfReach", {"robot", "ik", "--pose", "2.5,0,0.3,0,-3.14159,0"}, "out of reach", 1},
        BadInput{"ShortSeed",
                 {"robot", "ik", "--pose", "0.4,-0.4,0.25,0,-3.14159,1.57", "--seed", "1,2"},
                 "--seed: expected 6",
                 2}),
    [](const ::testing::TestParamInfo<BadInput>& info) { return info.param.name; });

TEST(RobotCommand, MalformedUrdfSaysWhere) {
  const auto dir = arcplan::testing::freshTempDirectory("robot_bad_urdf");
  std::ofstream(dir / "bad.urdf") << "<robot name=\"r\">\n<link name=\"a\">\n</robot>\n";
  const auto result = runArcplan({"robot", "fk", "--joints", "0,0,0,0,0,0", "--urdf", (dir / "bad.urdf").string()});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find("bad.urdf:"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("malformed XML"), std::string::npos) << result.err;
}

TEST(RobotCommand, HelpDescribesSubcommands) {
  const auto result = runArcplan({"robot", "--help"});
  EXPECT_EQ(result.exitCode, 0);
  EXPECT_NE(result.out.find("fk"), std::string::npos);
  EXPECT_NE(result.out.find("ik"), std::string::npos);
}

}  // namespace
