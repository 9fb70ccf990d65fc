// `arcplan plan --seed S` draws what a campaign run with run seed S draws (planners/seeded_sampling.h):
// the same RRTConnect + simplifier path, checked by comparing the two programs' outputs.
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

// RRTConnect on the beam scene, planned by `arcplan plan` as the campaign's run with `seed`.
nlohmann::json planWithSeed(const std::filesystem::path& scene, const std::string& seed,
                            const std::filesystem::path& csv) {
  const auto result = runArcplan({"plan", "--scene", scene.string(), "--planner", "RRTConnect", "--seed", seed,
                                  "--clearance", "0.01", "--vmax", "0.25", "--json", "-", "--path-csv", csv.string()});
  if (result.exitCode != 0) throw std::runtime_error("plan failed: " + result.err);
  return nlohmann::json::parse(result.out);
}

TEST(PlanSeed, PlanRepeatsTheCampaignsRRTConnectRunOfThatSeed) {
  const auto dir = freshTempDirectory("plan_seed_campaign");
  const auto scene = dir / "beam.yaml";
  {
    std::ofstream(scene) << kBeamScene;
    std::ofstream suite(dir / "suite.yaml");
    suite << "name: plan_seed\nruns: 2\ntime_limit: 5.0\nv_max: 0.25\nclearance: 0.01\n"
          << "problems:\n  - {name: beam, scene: " << scene.string() << ", query: over_the_beam}\n"
          << "planners:\n  - RRTConnect\n";
  }
  const auto campaign = runArcplan({"bench", "--suite", (dir / "suite.yaml").string(), "-j", "1", "--no-plots",
                                    "--quiet", "--out", (dir / "campaign").string()});
  ASSERT_EQ(campaign.exitCode, 0) << campaign.err;
  const auto runs = databaseRows(dir / "campaign" / "benchmark.db",
                                 "SELECT run_seed, execution_time, tcp_path_length FROM runs ORDER BY id", "");
  ASSERT_EQ(runs.size(), 2u);
  ASSERT_NE(runs[0][0], runs[1][0]) << "the two runs share a seed: nothing would tell them apart";
  for (std::size_t run = 0; run < runs.size(); ++run) {
    const std::string& seed = runs[run][0];
    const nlohmann::json first = planWithSeed(scene, seed, dir / ("first" + seed + ".csv"));
    const nlohmann::json second = planWithSeed(scene, seed, dir / ("second" + seed + ".csv"));
    ASSERT_EQ(first["status"], "exact") << first.dump();
    // The same path twice ...
    EXPECT_EQ(readFile(dir / ("first" + seed + ".csv")), readFile(dir / ("second" + seed + ".csv")));
    // ... and the campaign's: the database keeps the run's measurements, not its path.
    const double executionTime = std::stod(runs[run][1]), tcpLength = std::stod(runs[run][2]);
    EXPECT_NEAR(first["execution_time_s"].get<double>(), executionTime, 1e-6 * executionTime) << "seed " << seed;
    EXPECT_NEAR(first["tcp_path_length_m"].get<double>(), tcpLength, 1e-6 * tcpLength) << "seed " << seed;
  }
  // The two run seeds give two paths, so agreeing on both is not a coincidence of one path.
  EXPECT_NE(runs[0][1], runs[1][1]);
}

}  // namespace
}  // namespace arcplan::testing
