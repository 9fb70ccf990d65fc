// Facts that two commands both report come from one computation (issue 24): `robot check --query`
// checks the configurations `plan` starts and ends at, and `plan` and `bench` measure the same
// clearance for the same path.
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/command.h"
#include "support/database_rows.h"

namespace arcplan::testing {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(ARCPLAN_TEST_DATA_DIR) / "scenes";

nlohmann::json jsonFile(const std::filesystem::path& file) { return nlohmann::json::parse(readFile(file)); }

// The rows of a joint-path CSV (header q0..q5).
std::vector<std::vector<double>> pathRows(const std::filesystem::path& file) {
  std::istringstream in(readFile(file));
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

void expectSameJoints(const nlohmann::json& checked, const std::vector<double>& planned, const char* end) {
  SCOPED_TRACE(end);
  ASSERT_EQ(checked.size(), 6u);
  ASSERT_EQ(planned.size(), 6u);
  for (std::size_t j = 0; j < 6; ++j) EXPECT_NEAR(checked[j].get<double>(), planned[j], 1e-9) << "joint " << j;
}

// The thesis query without its seeds: the IK solution nearest the zero configuration (what `robot
// check` took) is another branch than the collision-free one nearest the default seed (`plan`'s).
TEST(CommandAgreement, RobotCheckChecksTheEndpointsPlanUses) {
  const auto dir = freshTempDirectory("agreement_endpoints");
  std::string scene = readFile(kScenes / "thesis_obstacle.yaml");
  for (std::size_t at = scene.find("      seed:"); at != std::string::npos; at = scene.find("      seed:")) {
    scene.erase(at, scene.find('\n', at) + 1 - at);
  }
  ASSERT_EQ(scene.find("seed:"), std::string::npos);
  const auto sceneFile = dir / "unseeded.yaml";
  std::ofstream(sceneFile) << scene;

  const auto check = runArcplan(
      {"robot", "check", "--scene", sceneFile.string(), "--query", "A_to_B", "--json", (dir / "check.json").string()});
  ASSERT_EQ(check.exitCode, 0) << check.err;
  const auto plan = runArcplan({"plan", "--scene", sceneFile.string(), "--query", "A_to_B", "--planner", "arc",
                                "--path-csv", (dir / "path.csv").string()});
  ASSERT_EQ(plan.exitCode, 0) << plan.err;
  const auto checked = jsonFile(dir / "check.json");
  const auto path = pathRows(dir / "path.csv");
  ASSERT_GE(path.size(), 2u);
  expectSameJoints(checked.at("start").at("joints"), path.front(), "start");
  expectSameJoints(checked.at("goal").at("joints"), path.back(), "goal");
  EXPECT_TRUE(checked.at("valid").get<bool>());
}

const std::vector<std::string> kArcThesisParameters{"--param", "sagitta=0.2",      "--param", "half_chord=0.2",
                                                    "--param", "entry_radius=0.1", "--param", "exit_radius=0.2"};

nlohmann::json planJson(const std::filesystem::path& dir, const std::string& name,
                        const std::vector<std::string>& extra) {
  std::vector<std::string> arguments{"plan",
                                     "--scene",
                                     (kScenes / "thesis_obstacle.yaml").string(),
                                     "--planner",
                                     "arc",
                                     "--json",
                                     (dir / name).string()};
  arguments.insert(arguments.end(), kArcThesisParameters.begin(), kArcThesisParameters.end());
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  const auto result = runArcplan(arguments);
  EXPECT_EQ(result.exitCode, 0) << result.err;
  return jsonFile(dir / name);
}

// The thesis arc (deterministic) planned once by `plan` and once in a one-run campaign.
TEST(CommandAgreement, PlanAndBenchMeasureTheSameClearanceForTheSamePath) {
  const auto dir = freshTempDirectory("agreement_clearance");
  const auto suite = dir / "one.yaml";
  std::ofstream(suite) << "name: one\nruns: 1\ntime_limit: 1.0\nv_max: 0.25\nclearance: 0.01\n"
                       << "problems:\n  - {name: obstacle, scene: " << (kScenes / "thesis_obstacle.yaml").string()
                       << ", query: A_to_B}\n"
                       << "planners:\n  - {name: arc-h1.00r, planner: arc, params: {sagitta: 0.2, half_chord: 0.2, "
                          "entry_radius: 0.1, exit_radius: 0.2}}\n";
  const auto bench = runArcplan(
      {"bench", "--suite", suite.string(), "--no-plots", "--quiet", "-j", "1", "--out", (dir / "bench").string()});
  ASSERT_EQ(bench.exitCode, 0) << bench.err;
  const auto rows = databaseRows(dir / "bench" / "benchmark.db",
                                 "SELECT min_clearance, tcp_path_length, execution_time FROM runs", "");
  ASSERT_EQ(rows.size(), 1u);
  const double benchClearance = std::stod(rows[0][0]);

  const auto scaled = planJson(dir, "scaled.json", {"--vmax", "0.25"});
  const auto unscaled = planJson(dir, "unscaled.json", {});
  // The same path: its TCP length and execution time agree to the log's 10 digits.
  EXPECT_NEAR(scaled.at("tcp_path_length_m").get<double>(), std::stod(rows[0][1]), 1e-9);
  EXPECT_NEAR(scaled.at("execution_time_s").get<double>(), std::stod(rows[0][2]), 1e-8);
  // The particle is 0.01 m from the straight line's TCP; the arc passes it at several centimetres.
  EXPECT_GT(benchClearance, 0.01);
  EXPECT_NEAR(scaled.at("min_clearance_m").get<double>(), benchClearance, 1e-10);
  EXPECT_NEAR(unscaled.at("min_clearance_m").get<double>(), benchClearance, 1e-10);
  EXPECT_NEAR(unscaled.at("tcp_path_length_m").get<double>(), scaled.at("tcp_path_length_m").get<double>(), 1e-12);
}

}  // namespace
}  // namespace arcplan::testing
