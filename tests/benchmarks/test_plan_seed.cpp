// `arcplan plan --seed S` draws what a campaign run with run seed S draws (planners::seedRun): the same
// RRTConnect + simplifier path, and the same arc-auto path (its fallback seeded with S), checked by
// comparing the two programs' outputs.
#include <gtest/gtest.h>

#include <stdexcept>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/command.h"
#include "support/database_rows.h"

namespace arcplan::testing {
namespace {

// The generated suite's forearm-beam-009 (seed 20240611) as a scene file: a beam at the elbow's height
// near the base axis. RRTConnect + simplifier paths differ from seed to seed here (the thesis scenes
// simplify to one straight motion whatever the seed, which would not tell two seeds apart).
const char* const kBeamScene = R"(name: elbow_beam
robot: ur10e
obstacles:
  - name: table
    box: {size: [2.0, 2.0, 0.05]}
    position: [0.0, 0.0, -0.025]
  - name: beam
    box: {size: [1.19452611899725, 0.0447951560837569, 0.0945077526952936]}
    position: [0.195507084341427, -0.00222967505255894, 0.755856014615223]
    rpy: [0, 0, 2.83093548283307]
allowed_collisions:
  - [table, base_link_inertia]
  - [table, shoulder_link]
queries:
  - name: over_the_beam
    start:
      joints: [1.2455732027649, -1.9210789748523, 2.46788163520193, -2.11759898714453, -1.57079632679489, 1.2455732027649]
    goal:
      joints: [0.607349460295433, -1.01925237738874, 1.9625322279851, -2.51407617739126, -1.5707963267949, 0.607349460295433]
)";

// A planner as the suite names it and as `arcplan plan` asks for it. The arc planner's line-and-arc search
// has a wall-clock deadline; off here so both programs do the same work whatever the machine's load.
struct SeededPlanner {
  std::string label;
  std::string suiteEntry;
  std::vector<std::string> planArguments;
};
const std::vector<SeededPlanner> kSeededPlanners{
    {"RRTConnect", "RRTConnect", {"--planner", "RRTConnect"}},
    // The arc planner's `seed` is not given: both programs set it to the run seed (planners::seedRun).
    {"arc-auto",
     "{name: arc-auto, planner: arc, params: {auto: 1, deadline: 0}}",
     {"--planner", "arc", "--param", "auto=1", "--param", "deadline=0"}},
};

// `planner` on the beam scene, planned by `arcplan plan` as the campaign's run with `seed`.
nlohmann::json planWithSeed(const SeededPlanner& planner, const std::filesystem::path& scene, const std::string& seed,
                            const std::filesystem::path& csv) {
  std::vector<std::string> arguments{"plan", "--scene", scene.string()};
  arguments.insert(arguments.end(), planner.planArguments.begin(), planner.planArguments.end());
  for (const std::string& argument :
       {std::string("--seed"), seed, std::string("--clearance"), std::string("0.01"), std::string("--vmax"),
        std::string("0.25"), std::string("--json"), std::string("-"), std::string("--path-csv"), csv.string()})
    arguments.push_back(argument);
  const auto result = runArcplan(arguments);
  if (result.exitCode != 0) throw std::runtime_error("plan failed: " + result.err);
  return nlohmann::json::parse(result.out);
}

TEST(PlanSeed, PlanRepeatsTheCampaignsRunOfThatSeedForRRTConnectAndArcAuto) {
  const auto dir = freshTempDirectory("plan_seed_campaign");
  const auto scene = dir / "beam.yaml";
  {
    std::ofstream(scene) << kBeamScene;
    std::ofstream suite(dir / "suite.yaml");
    suite << "name: plan_seed\nruns: 2\ntime_limit: 5.0\nv_max: 0.25\nclearance: 0.01\n"
          << "problems:\n  - {name: beam, scene: " << scene.string() << ", query: over_the_beam}\n"
          << "planners:\n";
    for (const SeededPlanner& planner : kSeededPlanners) suite << "  - " << planner.suiteEntry << "\n";
  }
  const auto campaign = runArcplan({"bench", "--suite", (dir / "suite.yaml").string(), "-j", "1", "--no-plots",
                                    "--quiet", "--out", (dir / "campaign").string()});
  ASSERT_EQ(campaign.exitCode, 0) << campaign.err;
  for (const SeededPlanner& planner : kSeededPlanners) {
    const auto runs = databaseRows(dir / "campaign" / "benchmark.db",
                                   "SELECT r.run_seed, r.execution_time, r.tcp_path_length FROM runs r JOIN "
                                   "plannerConfigs p ON p.id = r.plannerid WHERE p.name = 'geometric_" +
                                       planner.label + "' ORDER BY r.id",
                                   "");
    ASSERT_EQ(runs.size(), 2u) << planner.label;
    ASSERT_NE(runs[0][0], runs[1][0]) << "the two runs share a seed: nothing would tell them apart";
    for (std::size_t run = 0; run < runs.size(); ++run) {
      const std::string& seed = runs[run][0];
      const auto first = dir / (planner.label + "first" + seed + ".csv");
      const auto second = dir / (planner.label + "second" + seed + ".csv");
      const nlohmann::json planned = planWithSeed(planner, scene, seed, first);
      planWithSeed(planner, scene, seed, second);
      ASSERT_EQ(planned["status"], "exact") << planned.dump();
      // The same path twice ...
      EXPECT_EQ(readFile(first), readFile(second)) << planner.label;
      // ... and the campaign's: the database keeps the run's measurements, not its path.
      const double executionTime = std::stod(runs[run][1]), tcpLength = std::stod(runs[run][2]);
      EXPECT_NEAR(planned["execution_time_s"].get<double>(), executionTime, 1e-6 * executionTime)
          << planner.label << " seed " << seed;
      EXPECT_NEAR(planned["tcp_path_length_m"].get<double>(), tcpLength, 1e-6 * tcpLength)
          << planner.label << " seed " << seed;
    }
    if (planner.label == "RRTConnect") {
      // The two run seeds give two paths, so agreeing on both is not a coincidence of one path.
      EXPECT_NE(runs[0][1], runs[1][1]);
    }
  }
}

}  // namespace
}  // namespace arcplan::testing
