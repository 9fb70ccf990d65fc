// `arcplan plan` end to end: results, files, determinism with --seed, and every bad-input error.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "arcplan/trajectory/joint_path.h"
#include "support/command.h"

namespace {

using arcplan::testing::freshTempDirectory;
using arcplan::testing::readFile;
using arcplan::testing::runArcplan;

std::string scene(const std::string& name) { return std::string(ARCPLAN_TEST_DATA_DIR) + "/scenes/" + name + ".yaml"; }

TEST(PlanCommand, ThesisCaseReportsMetricsAndWritesJsonAndPath) {
  const auto dir = freshTempDirectory("plan_thesis");
  const auto json = dir / "plan.json", csv = dir / "path.csv";
  const auto result = runArcplan({"plan", "--scene", scene("thesis_obstacle"), "--param", "sagitta=0.1", "--json",
                                  json.string(), "--path-csv", csv.string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("status              exact"), std::string::npos) << result.out;
  const auto document = nlohmann::json::parse(readFile(json));
  EXPECT_EQ(document["status"], "exact");
  EXPECT_EQ(document["planner"], "arc");
  EXPECT_EQ(document["query"], "A_to_B");
  EXPECT_FALSE(document.contains("reason"));
  // Thesis Table 3.3 case (d): 0.8816 m.
  EXPECT_NEAR(document["tcp_path_length_m"].get<double>(), 0.8816, 0.004 * 0.8816);
  EXPECT_GT(document["joint_path_length_rad"].get<double>(), 0.0);
  EXPECT_GT(document["min_clearance_m"].get<double>(), 0.05);  // h = 0.1 m over a 1 cm particle
  EXPECT_GT(document["solve_time_s"].get<double>(), 0.0);
  EXPECT_EQ(document["simplification_time_s"].get<double>(), 0.0);  // a pure arc path: nothing to simplify
  EXPECT_EQ(document["parameters"]["sagitta"], "0.1");
  EXPECT_EQ(document["arc"]["detours"].size(), 1u);
  EXPECT_FALSE(document.contains("fallback_reason"));  // lines and arcs only
  const auto path = arcplan::trajectory::readJointPathCsv(csv);
  EXPECT_EQ(path.size(), document["waypoints"].get<std::size_t>());
}

// Start and goal with the wrist on opposite sides of q5 = 0: no TCP path joins them, so the joint-space fallback
// answers, and `plan` says why the line search gave up and what the fallback kept.
TEST(PlanCommand, AFallbackPathSaysWhyTheLineSearchGaveUp) {
  const auto dir = freshTempDirectory("plan_fallback");
  std::ofstream(dir / "wrist_flip.yaml")
      << "name: wrist_flip\nrobot: ur10e\nobstacles:\n"
         "  - {name: table, box: {size: [2.0, 2.0, 0.05]}, position: [0, 0, -0.025]}\n"
         "allowed_collisions: [[table, base_link_inertia], [table, shoulder_link]]\n"
         "queries:\n  - name: flip\n"
         "    start: {joints: [-1.098, -1.510, 2.351, -2.411, -1.571, -1.098]}\n"
         "    goal: {joints: [0.399, -1.624, 2.012, -1.958, 1.571, 0.399]}\n";
  const auto json = dir / "plan.json";
  const auto result =
      runArcplan({"plan", "--scene", (dir / "wrist_flip.yaml").string(), "--seed", "1", "--json", json.string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto document = nlohmann::json::parse(readFile(json));
  ASSERT_EQ(document["mode"], "fallback");
  const std::string why = document["fallback_reason"];
  EXPECT_EQ(why.rfind("branch change: start and goal are on different IK branches", 0), 0u) << why;
  EXPECT_NE(why.find("differ in the wrist"), std::string::npos) << why;
  EXPECT_NE(why.find("the fallback kept"), std::string::npos) << why;
  EXPECT_FALSE(document.contains("reason"));  // an exact path: nothing failed
  EXPECT_NE(result.out.find("fallback reason     branch change"), std::string::npos) << result.out;
}

TEST(PlanCommand, JsonOnStdoutIsTheOnlyOutput) {
  const auto result = runArcplan({"plan", "--scene", scene("thesis_free"), "--json", "-"});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto document = nlohmann::json::parse(result.out);
  EXPECT_EQ(document["status"], "exact");
  EXPECT_NEAR(document["tcp_path_length_m"].get<double>(), 0.8331, 0.004 * 0.8331);
}

TEST(PlanCommand, TimesOmplsSimplifierApartFromTheSolveTime) {
  const auto result = runArcplan(
      {"plan", "--scene", scene("thesis_obstacle"), "--planner", "RRTConnect", "--seed", "3", "--json", "-"});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto document = nlohmann::json::parse(result.out);
  // The simplifier ran on RRTConnect's path (at least one shortcut pass with motion checks): a measured time.
  EXPECT_GT(document["simplification_time_s"].get<double>(), 0.0);
  EXPECT_GT(document["solve_time_s"].get<double>(), 0.0);
}

TEST(PlanCommand, SeedMakesASamplingPlannerReproducible) {
  const auto dir = freshTempDirectory("plan_seed");
  std::string paths[2];
  for (int run = 0; run < 2; ++run) {
    const auto csv = dir / ("rrt" + std::to_string(run) + ".csv");
    const auto result = runArcplan({"plan", "--scene", scene("thesis_obstacle"), "--planner", "rrtconnect", "--seed",
                                    "42", "--param", "range=0.5", "--path-csv", csv.string()});
    ASSERT_EQ(result.exitCode, 0) << result.err;
    paths[run] = readFile(csv);
  }
  EXPECT_FALSE(paths[0].empty());
  EXPECT_EQ(paths[0], paths[1]);
}

TEST(PlanCommand, VmaxAddsTheScaledMetrics) {
  const auto result = runArcplan(
      {"plan", "--scene", scene("thesis_obstacle"), "--param", "sagitta=0.1", "--vmax", "0.25", "--json", "-"});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto document = nlohmann::json::parse(result.out);
  EXPECT_GT(document["execution_time_s"].get<double>(), 0.8816 / 0.25);  // cannot beat cruising all the way
  EXPECT_LE(document["peak_tcp_speed_mps"].get<double>(), 0.25 + 1e-9);
  EXPECT_DOUBLE_EQ(document["vmax_mps"].get<double>(), 0.25);
}

TEST(PlanCommand, FailedPlanSaysWhyWritesJsonAndNoPath) {
  const auto dir = freshTempDirectory("plan_failed");
  const auto json = dir / "plan.json", csv = dir / "path.csv";
  const auto result = runArcplan({"plan", "--scene", scene("thesis_obstacle"), "--param", "sagitta=0.35", "--param",
                                  "half_chord=0.35", "--json", json.string(), "--path-csv", csv.string()});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find("arcplan: error: planner arc found no path"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("|AO|"), std::string::npos) << result.err;
  const auto document = nlohmann::json::parse(readFile(json));
  EXPECT_EQ(document["status"], "failed");
  EXPECT_NE(document["reason"].get<std::string>().find("particle"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(csv));
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(entry.path(), json) << "unexpected file " << entry.path();
  }
}

// RRT with steps of 1e-4 rad cannot reach a goal about 2 rad away in 0.05 s (that needs > 20000
// tree extensions): it returns its best approximate path, which is refused unless asked for.
TEST(PlanCommand, ApproximatePathNeedsAllowApproximate) {
  const auto dir = freshTempDirectory("plan_approximate");
  const auto json = dir / "plan.json", csv = dir / "path.csv";
  const std::vector<std::string> arguments{"plan",         "--scene",    scene("thesis_free"),
                                           "--planner",    "RRT",        "--param",
                                           "range=0.0001", "--time",     "0.05",
                                           "--seed",       "1",          "--json",
                                           json.string(),  "--path-csv", csv.string()};
  const auto refused = runArcplan(arguments);
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_NE(refused.err.find("found only an approximate path (--allow-approximate accepts it)"), std::string::npos)
      << refused.err;
  EXPECT_EQ(nlohmann::json::parse(readFile(json))["status"], "approximate");
  EXPECT_FALSE(std::filesystem::exists(csv));

  auto accepting = arguments;
  accepting.push_back("--allow-approximate");
  const auto accepted = runArcplan(accepting);
  EXPECT_EQ(accepted.exitCode, 0) << accepted.err;
  EXPECT_NE(accepted.err.find("warning: RRT returned an approximate path"), std::string::npos) << accepted.err;
  const auto document = nlohmann::json::parse(readFile(json));
  EXPECT_EQ(document["status"], "approximate");
  EXPECT_NE(document["reason"].get<std::string>().find("from the goal"), std::string::npos);
  ASSERT_TRUE(std::filesystem::exists(csv));
  EXPECT_EQ(arcplan::trajectory::readJointPathCsv(csv).size(), document["waypoints"].get<std::size_t>());
}

TEST(PlanCommand, BadInputIsRejectedWithAClearMessage) {
  const struct {
    std::vector<std::string> arguments;
    std::string message;
  } cases[] = {
      {{"plan", "--scene", "no_such_scene.yaml"}, "no_such_scene.yaml"},
      {{"plan", "--scene", scene("thesis_free"), "--planner", "RRTConect"}, "unknown planner 'RRTConect'"},
      {{"plan", "--scene", scene("thesis_free"), "--param", "range"}, "--param expects NAME=VALUE"},
      {{"plan", "--scene", scene("thesis_free"), "--planner", "RRT", "--param", "rang=1"},
       "RRT has no parameter 'rang'"},
      {{"plan", "--scene", scene("thesis_free"), "--param", "sagitta=high"},
       "parameter 'sagitta' does not accept 'high'"},
      {{"plan", "--scene", scene("thesis_free"), "--query", "nowhere"}, "nowhere"},
  };
  for (const auto& c : cases) {
    const auto dir = freshTempDirectory("plan_bad");
    auto arguments = c.arguments;
    arguments.insert(arguments.end(),
                     {"--json", (dir / "out.json").string(), "--path-csv", (dir / "path.csv").string()});
    const auto result = runArcplan(arguments);
    EXPECT_EQ(result.exitCode, 1) << c.message;
    EXPECT_NE(result.err.find(c.message), std::string::npos) << "expected '" << c.message << "' in: " << result.err;
    EXPECT_TRUE(std::filesystem::is_empty(dir)) << c.message;
  }
  const auto missingScene = runArcplan({"plan"});
  EXPECT_NE(missingScene.exitCode, 0);
  EXPECT_NE(missingScene.err.find("--scene"), std::string::npos) << missingScene.err;
}

TEST(PlanCommand, HelpDescribesTheOptions) {
  const auto result = runArcplan({"plan", "--help"});
  EXPECT_EQ(result.exitCode, 0);
  for (const char* option :
       {"--scene", "--query", "--planner", "--param", "--time", "--seed", "--json", "--path-csv", "--vmax"}) {
    EXPECT_NE(result.out.find(option), std::string::npos) << option;
  }
}

}  // namespace
