// `arcplan scale` end to end: metrics on stdout and in JSON, the timed trajectory CSV, the plot, and
// one test per kind of bad input (message, non-zero exit, no output file written).
#include <fstream>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "arcplan/robot/robot_model.h"
#include "arcplan/trajectory/joint_path.h"
#include "straight_line.h"
#include "support/command.h"

namespace arcplan::trajectory {
namespace {

namespace fs = std::filesystem;
using arcplan::testing::readFile;
using arcplan::testing::runArcplan;

const std::string kScene = std::string(ARCPLAN_TEST_DATA_DIR) + "/scenes/thesis_free.yaml";

fs::path writeLinePath(const fs::path& dir) {
  const fs::path file = dir / "line.csv";
  writeJointPathCsv(file, testing::straightLinePath(robot::ur10e(), 100));
  return file;
}

fs::path writeText(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

TEST(ScaleCommand, ThesisLineMetricsTrajectoryAndPlot) {
  const auto dir = arcplan::testing::freshTempDirectory("scale_line");
  const auto path = writeLinePath(dir);
  const auto result =
      runArcplan({"scale", "--scene", kScene, "--path-csv", path.string(), "--json", (dir / "m.json").string(),
                  "--traj-csv", (dir / "t.csv").string(), "--plot", (dir / "speed.png").string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("execution time"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("peak tcp speed"), std::string::npos);

  const auto json = nlohmann::json::parse(readFile(dir / "m.json"));
  for (const char* key : {"tcp_path_length_m", "joint_path_length_rad", "execution_time_s", "mean_tcp_speed_mps",
                          "peak_tcp_speed_mps", "time_above_limit_s", "min_clearance_m", "max_joint_speed_ratio"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  const double time = json["execution_time_s"].get<double>();
  EXPECT_LE(time, 3.55);
  EXPECT_GE(time, 0.8331 / 0.25 + 0.2 - 1e-3);  // L/v + rise time
  EXPECT_LE(json["peak_tcp_speed_mps"].get<double>(), 0.25);
  EXPECT_EQ(json["time_above_limit_s"].get<double>(), 0.0);
  EXPECT_EQ(json["settings"]["vmax_mps"].get<double>(), 0.25);

  std::ifstream csv(dir / "t.csv");
  std::string header, line, last;
  std::getline(csv, header);
  EXPECT_EQ(header.substr(0, 18), "t,q0,q1,q2,q3,q4,q");
  EXPECT_NE(header.find(",qdd5,tcp_speed,tcp_x,tcp_y,tcp_z"), std::string::npos) << header;
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    last = line;
  }
  EXPECT_EQ(rows, static_cast<std::size_t>(std::ceil(time / 0.002 - 1e-9)) + 1);  // every 2 ms, both ends
  EXPECT_NEAR(std::stod(last.substr(0, last.find(','))), time, 1e-6);

  const std::string png = readFile(dir / "speed.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(ScaleCommand, SpeedRiseAndAccelerationOptions) {
  const auto dir = arcplan::testing::freshTempDirectory("scale_options");
  const auto path = writeLinePath(dir);
  const auto slow =
      runArcplan({"scale", "--path-csv", path.string(), "--vmax", "0.149", "--rise", "0.5", "--json", "-"});
  ASSERT_EQ(slow.exitCode, 0) << slow.err;
  const auto json = nlohmann::json::parse(slow.out.substr(slow.out.find('{')));
  EXPECT_GE(json["execution_time_s"].get<double>(), 0.8331 / 0.149 + 0.5 - 1e-3);
  EXPECT_LE(json["execution_time_s"].get<double>(), 0.8331 / 0.149 + 0.5 + 0.02);
  EXPECT_LE(json["peak_tcp_speed_mps"].get<double>(), 0.149);

  const auto accelerated = runArcplan({"scale", "--path-csv", path.string(), "--max-acc", "2.5", "--json", "-"});
  ASSERT_EQ(accelerated.exitCode, 0) << accelerated.err;
  const auto fast = nlohmann::json::parse(accelerated.out.substr(accelerated.out.find('{')));
  EXPECT_LE(fast["execution_time_s"].get<double>(), 0.8331 / 0.25 + 0.1 + 0.02);  // ramps of 0.25/2.5 = 0.1 s
}

// Runs a failing command and checks the message, the exit code and that no output was written.
void expectFailure(const std::vector<std::string>& arguments, const fs::path& dir, const std::string& expected) {
  std::vector<std::string> full = arguments;
  full.insert(full.end(), {"--json", (dir / "out.json").string(), "--traj-csv", (dir / "out.csv").string()});
  const auto result = runArcplan(full);
  EXPECT_NE(result.exitCode, 0);
  EXPECT_NE(result.err.find(expected), std::string::npos) << "stderr: " << result.err;
  EXPECT_FALSE(fs::exists(dir / "out.json"));
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
}

TEST(ScaleCommand, NonPositiveSpeedLimit) {
  const auto dir = arcplan::testing::freshTempDirectory("scale_vmax");
  const auto path = writeLinePath(dir).string();
  expectFailure({"scale", "--path-csv", path, "--vmax", "0"}, dir, "--vmax must be a positive number (m/s), got 0");
  expectFailure({"scale", "--path-csv", path, "--vmax", "-0.25"}, dir, "--vmax must be a positive number");
  expectFailure({"scale", "--path-csv", path, "--vmax", "nan"}, dir, "--vmax");
  expectFailure({"scale", "--path-csv", path, "--rise", "0"}, dir, "--rise must be a positive number (s)");
  expectFailure({"scale", "--path-csv", path, "--max-acc", "-1"}, dir, "--max-acc must be a positive number");
}

TEST(ScaleCommand, NanInThePathFile) {
  const auto dir = arcplan::testing::freshTempDirectory("scale_nan");
  const auto file =
      writeText(dir / "bad.csv", "q0,q1,q2,q3,q4,q5\n-1.1,-1.5,2.3,-2.4,-1.57,-1.1\n-1.1,nan,2.3,-2.4,-1.57,-1.1\n");
  expectFailure({"scale", "--path-csv", file.string()}, dir, file.string() + ":3: column q1");
}

TEST(ScaleCommand, WrongColumnCount) {
  const auto dir = arcplan::testing::freshTempDirectory("scale_columns");
  const auto file =
      writeText(dir / "bad.csv", "q0,q1,q2,q3,q4,q5\n-1.1,-1.5,2.3,-2.4,-1.57,-1.1\n-1.1,-1.5,2.3,-2.4,-1.57\n");
  expectFailure({"scale", "--path-csv", file.string()}, dir, ":3: expected 6 comma-separated joint angles");
}

TEST(ScaleCommand, PathLeavingTheJointLimits) {
  const auto dir = arcplan::testing::freshTempDirectory("scale_limits");
  const auto file =
      writeText(dir / "bad.csv", "q0,q1,q2,q3,q4,q5\n-1.1,-1.5,2.3,-2.4,-1.57,-1.1\n-1.1,-1.5,3.3,-2.4,-1.57,-1.1\n");
  expectFailure({"scale", "--scene", kScene, "--path-csv", file.string()}, dir,
                ":3: q2 (elbow_joint) = 3.3 rad is outside its limits");
}

TEST(ScaleCommand, MissingFilesAndBadOptions) {
  const auto dir = arcplan::testing::freshTempDirectory("scale_missing");
  const auto path = writeLinePath(dir).string();
  expectFailure({"scale", "--path-csv", (dir / "none.csv").string()}, dir, "cannot be opened");
  expectFailure({"scale", "--path-csv", path, "--urdf", (dir / "none.urdf").string()}, dir, "does not exist");
  expectFailure({"scale", "--path-csv", path, "--plot", (dir / "plot.svg").string()}, dir, "expected a .png");
  expectFailure({"scale"}, dir, "--path-csv");
}

TEST(ScaleCommand, HelpDescribesTheOptions) {
  const auto result = runArcplan({"scale", "--help"});
  EXPECT_EQ(result.exitCode, 0);
  for (const char* option :
       {"--scene", "--urdf", "--path-csv", "--vmax", "--rise", "--max-acc", "--json", "--traj-csv", "--plot"}) {
    EXPECT_NE(result.out.find(option), std::string::npos) << option;
  }
}

}  // namespace
}  // namespace arcplan::trajectory
