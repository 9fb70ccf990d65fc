// Every planner plans the problem's clearance (benchmarks::keepProblemClearance): the arc planner keeps a
// clearance of its own (1 cm unless set, the larger of its own and the problem's), so in a campaign whose suite
// asks for less it is lowered to the suite's, as `plan --clearance` does; a clearance the suite sets for the
// planner stays. Read back from what the runs recorded: OMPL's planner settings in the database, the JSON of `plan`.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "support/command.h"
#include "support/database_rows.h"

namespace arcplan::testing {
namespace {

// The `clearance = ...` line of each planner configuration's recorded settings.
std::map<std::string, std::string> recordedClearances(const std::filesystem::path& database) {
  std::map<std::string, std::string> clearances;
  for (const auto& row : databaseRows(database, "SELECT name, settings FROM plannerConfigs")) {
    const std::string& settings = row[1];
    const std::string key = "clearance = ";
    const auto at = settings.find(key);
    clearances[row[0]] =
        at == std::string::npos ? "" : settings.substr(at + key.size(), settings.find('\n', at) - at - key.size());
  }
  return clearances;
}

std::map<std::string, std::string> campaignAt(const std::string& name, const std::string& clearance) {
  const auto dir = freshTempDirectory("problem_clearance_" + name);
  std::ofstream(dir / "suite.yaml") << "name: " << name
                                    << "\nruns: 1\ntime_limit: 2\nv_max: 0.25\nclearance: " << clearance
                                    << "\nproblems: [{name: straight, scene: scenes/thesis_free.yaml}]\n"
                                       "planners:\n"
                                       "  - {name: arc-auto, planner: arc, params: {auto: 1}}\n"
                                       "  - {name: arc-own, planner: arc, params: {auto: 1, clearance: 0.02}}\n"
                                       "  - RRTConnect\n";
  const auto out = dir / "campaign";
  const auto bench = runArcplan(
      {"bench", "--suite", (dir / "suite.yaml").string(), "--no-plots", "--quiet", "-j", "1", "--out", out.string()});
  EXPECT_EQ(bench.exitCode, 0) << bench.err;
  return recordedClearances(out / "benchmark.db");
}

TEST(ProblemClearance, ACampaignLowersTheArcPlannersOwnClearanceToTheSuites) {
  const auto clearances = campaignAt("clearance_4mm", "0.004");
  EXPECT_EQ(clearances.at("geometric_arc-auto"), "0.004");
  EXPECT_EQ(clearances.at("geometric_arc-own"), "0.02");  // set by the suite for that planner: kept
  EXPECT_EQ(clearances.at("geometric_RRTConnect"), "");   // no clearance of its own
}

TEST(ProblemClearance, ALargerSuiteClearanceLeavesTheArcPlannersOwn) {
  // The planner keeps the larger of the two (its paths keep the suite's 5 cm, the campaign judges them so).
  const auto clearances = campaignAt("clearance_5cm", "0.05");
  EXPECT_EQ(clearances.at("geometric_arc-auto"), "0.01");
  EXPECT_EQ(clearances.at("geometric_arc-own"), "0.02");
}

nlohmann::json planned(const std::vector<std::string>& extra) {
  const auto dir = freshTempDirectory("problem_clearance_plan");
  std::vector<std::string> arguments{"plan", "--scene", "scenes/thesis_free.yaml",   "--planner",
                                     "arc",  "--json",  (dir / "plan.json").string()};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  const auto result = runArcplan(arguments);
  EXPECT_EQ(result.exitCode, 0) << result.err;
  return nlohmann::json::parse(readFile(dir / "plan.json"));
}

TEST(ProblemClearance, PlanLowersItWhereAClearanceIsAskedFor) {
  EXPECT_EQ(planned({"--clearance", "0.004"})["parameters"]["clearance"], "0.004");
  EXPECT_EQ(planned({"--clearance", "0.004", "--param", "clearance=0.02"})["parameters"]["clearance"], "0.02");
  // Without --clearance the arc planner keeps its own 1 cm.
  EXPECT_EQ(planned({})["parameters"]["clearance"], "0.01");
}

}  // namespace
}  // namespace arcplan::testing
