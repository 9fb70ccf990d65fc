// Joint path CSV: round trip, comments, and one test per kind of bad input (message names file and
// line; nothing half-written).
#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/trajectory/joint_path.h"
#include "support/command.h"

namespace arcplan::trajectory {
namespace {

namespace fs = std::filesystem;

fs::path writeText(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

std::string readError(const fs::path& file, const robot::RobotModel* model = nullptr) {
  try {
    if (model != nullptr) {
      readJointPathCsv(file, *model);
    } else {
      readJointPathCsv(file);
    }
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}

robot::Vector6 configuration(double base) {
  robot::Vector6 q;
  q << base, -1.5, 2.0, -2.0, -1.5707963267948966, base + 0.1;
  return q;
}

TEST(JointPathCsv, RoundTripIsExact) {
  const auto dir = testing::freshTempDirectory("joint_path_round_trip");
  JointPath path{configuration(-1.0983245), configuration(0.1 / 3.0), configuration(M_PI / 7.0)};
  path[1][3] = -6.283185307179586;  // a joint exactly at its limit survives the round trip too
  writeJointPathCsv(dir / "path.csv", path);
  const std::string text = testing::readFile(dir / "path.csv");
  EXPECT_EQ(text.substr(0, text.find('\n')), "q0,q1,q2,q3,q4,q5");
  const JointPath read = readJointPathCsv(dir / "path.csv");
  ASSERT_EQ(read.size(), path.size());
  for (std::size_t i = 0; i < path.size(); ++i) EXPECT_EQ(read[i], path[i]) << "waypoint " << i;
  EXPECT_TRUE(fs::exists(dir / "path.csv"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << "temporary file left behind";
}

TEST(JointPathCsv, CommentsBlankLinesAndSpacesAreAllowed) {
  const auto dir = testing::freshTempDirectory("joint_path_comments");
  const auto file = writeText(
      dir / "path.csv", "# planner: arc\n\n q0, q1 ,q2,q3,q4,q5\n# start\n0,0,0,0,0,0\n\n1, 2.5e-1 ,-3,4,5,+6\r\n");
  const JointPath path = readJointPathCsv(file);
  ASSERT_EQ(path.size(), 2u);
  EXPECT_EQ(path[1][1], 0.25);
  EXPECT_EQ(path[1][2], -3.0);
  EXPECT_EQ(path[1][5], 6.0);
}

TEST(JointPathCsv, NanNamesFileLineAndColumn) {
  const auto dir = testing::freshTempDirectory("joint_path_nan");
  const auto file = writeText(dir / "path.csv", "q0,q1,q2,q3,q4,q5\n0,0,0,0,0,0\n# comment\n0,0,nan,0,0,0\n");
  const std::string message = readError(file);
  EXPECT_EQ(message.rfind(file.string() + ":4: column q2: ", 0), 0u) << message;
  EXPECT_NE(message.find("not a finite"), std::string::npos) << message;
  EXPECT_NE(readError(writeText(dir / "inf.csv", "q0,q1,q2,q3,q4,q5\n0,0,0,0,0,inf\n0,0,0,0,0,0\n"))
                .find("inf.csv:2: column q5"),
            std::string::npos);
}

TEST(JointPathCsv, WrongColumnCount) {
  const auto dir = testing::freshTempDirectory("joint_path_columns");
  const auto file = writeText(dir / "path.csv", "q0,q1,q2,q3,q4,q5\n0,0,0,0,0,0\n0,0,0,0,0\n");
  const std::string message = readError(file);
  EXPECT_NE(message.find("path.csv:3: expected 6"), std::string::npos) << message;
  EXPECT_NE(message.find("found 5"), std::string::npos) << message;
  EXPECT_NE(readError(writeText(dir / "seven.csv", "q0,q1,q2,q3,q4,q5\n0,0,0,0,0,0,0\n")).find("found 7"),
            std::string::npos);
}

TEST(JointPathCsv, NonNumber) {
  const auto dir = testing::freshTempDirectory("joint_path_text");
  const std::string message =
      readError(writeText(dir / "path.csv", "q0,q1,q2,q3,q4,q5\n0,0,0,0,0,0\n0,0,0,1.5rad,0,0\n"));
  EXPECT_NE(message.find("path.csv:3: column q3: '1.5rad' is not a number"), std::string::npos) << message;
}

TEST(JointPathCsv, MissingOrWrongHeader) {
  const auto dir = testing::freshTempDirectory("joint_path_header");
  const std::string message = readError(writeText(dir / "path.csv", "# no header\n0,0,0,0,0,0\n1,1,1,1,1,1\n"));
  EXPECT_NE(message.find("path.csv:2: expected the header 'q0,q1,q2,q3,q4,q5'"), std::string::npos) << message;
}

TEST(JointPathCsv, EmptyFileAndTooFewWaypoints) {
  const auto dir = testing::freshTempDirectory("joint_path_short");
  EXPECT_NE(readError(writeText(dir / "empty.csv", "")).find("empty file"), std::string::npos);
  EXPECT_NE(readError(writeText(dir / "header.csv", "q0,q1,q2,q3,q4,q5\n")).find("at least 2 waypoints, found 0"),
            std::string::npos);
  EXPECT_NE(readError(writeText(dir / "one.csv", "q0,q1,q2,q3,q4,q5\n0,0,0,0,0,0\n")).find("found 1"),
            std::string::npos);
  EXPECT_NE(readError(dir / "missing.csv").find("cannot be opened"), std::string::npos);
}

TEST(JointPathCsv, JointLimitsCheckedAgainstTheModel) {
  const auto dir = testing::freshTempDirectory("joint_path_limits");
  // The UR10e elbow is limited to ±pi.
  const auto file = writeText(dir / "path.csv", "q0,q1,q2,q3,q4,q5\n0,0,0,0,0,0\n0,0,3.3,0,0,0\n");
  EXPECT_NO_THROW(readJointPathCsv(file));
  const std::string message = readError(file, &robot::ur10e());
  EXPECT_NE(message.find("path.csv:3: q2 (elbow_joint) = 3.3"), std::string::npos) << message;
  EXPECT_NE(message.find("outside its limits"), std::string::npos) << message;
}

TEST(JointPathCsv, FailedWriteLeavesNoFileBehind) {
  // The target is an existing directory: the final rename fails, the temporary file must go.
  const auto dir = testing::freshTempDirectory("joint_path_write");
  const fs::path target = dir / "occupied";
  fs::create_directories(target / "inside");
  EXPECT_THROW(writeJointPathCsv(target, {configuration(0.0), configuration(0.1)}), Error);
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << "temporary file left behind";
}

TEST(JointPath, ValidationAndLength) {
  const auto& model = robot::ur10e();
  const JointPath path{configuration(0.0), configuration(0.3), configuration(-0.1)};
  EXPECT_NO_THROW(validateJointPath(model, path, "path"));
  // Joint 0 and joint 5 move together: each step is sqrt(2)·|Δ|.
  EXPECT_NEAR(jointPathLength(path), std::sqrt(2.0) * (0.3 + 0.4), 1e-12);

  JointPath bad = path;
  bad[2][4] = NAN;
  try {
    validateJointPath(model, bad, "my path");
    FAIL() << "NaN accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("my path, waypoint 2"), std::string::npos) << error.what();
  }
  bad = path;
  bad[1][0] = 7.0;
  try {
    validateJointPath(model, bad, "path");
    FAIL() << "joint outside its limits accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("waypoint 1: q0 (shoulder_pan_joint) = 7"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(validateJointPath(model, {configuration(0.0)}, "path"), Error);
}

}  // namespace
}  // namespace arcplan::trajectory
