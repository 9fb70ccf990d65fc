// Reproducible campaigns (docs/reproducibility.md): with an iteration budget every run of the
// single-threaded planners is the same whether the campaign runs unsplit in one process, as two
// shards, or with two worker processes; the budget is recorded in campaign.json and in the logs.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "benchmarks/campaign_fixtures.h"
#include "support/command.h"
#include "support/database_rows.h"

namespace arcplan::testing {
namespace {

constexpr unsigned kBudget = 2000;

// The planners of docs/reproducibility.md's "deterministic with a budget" list that are cheap enough for a test.
const std::vector<std::string> kPlanners{"RRT", "RRTConnect", "RRTstar", "BiTRRT", "KPIECE1", "arc-auto"};

// One column of every run, in the database's run order.
std::vector<std::string> column(const std::filesystem::path& database, const std::string& name) {
  std::vector<std::string> values;
  for (const auto& row : databaseRows(database, "SELECT " + name + " FROM runs ORDER BY id")) values.push_back(row[0]);
  return values;
}

TEST(CampaignDeterminism, BudgetedRunsAreIdenticalAcrossShardLayoutsAndWorkerCounts) {
  const auto dir = freshTempDirectory("determinism");
  const auto suite = writeTinySuite(dir, kPlanners, 2, kBudget);

  const auto unsplit = dir / "unsplit", sharded = dir / "sharded", workers = dir / "workers";
  const auto one = runArcplan(benchArguments(suite, unsplit, {"-j", "1"}));
  ASSERT_EQ(one.exitCode, 0) << one.err;
  EXPECT_NE(one.err.find("runs of at most 20 s and 2000 iterations"), std::string::npos) << one.err;
  for (const char* shard : {"2/2", "1/2"}) {  // the second shard to finish builds the database
    const auto part = runArcplan(benchArguments(suite, sharded, {"-j", "1", "--shard", shard}));
    ASSERT_EQ(part.exitCode, 0) << part.err;
  }
  const auto two = runArcplan(benchArguments(suite, workers, {"-j", "2"}));
  ASSERT_EQ(two.exitCode, 0) << two.err;

  const auto reference = deterministicRuns(unsplit / "benchmark.db");
  ASSERT_EQ(reference.size(), 2u * kPlanners.size() * 2u);
  EXPECT_EQ(deterministicRuns(sharded / "benchmark.db"), reference);
  EXPECT_EQ(deterministicRuns(workers / "benchmark.db"), reference);

  // The budget, not the safety cap, ended every run: no run depends on the machine's speed.
  for (const auto& reached : column(unsplit / "benchmark.db", "time_cap_reached")) EXPECT_EQ(reached, "0");
  const auto iterations = column(unsplit / "benchmark.db", "iterations");
  for (const auto& used : iterations) EXPECT_LE(std::stoul(used), kBudget + 1);
  // Some runs spent the whole budget (the evaluation that ended them counted) and failed, others solved
  // early: both kinds are compared above.
  EXPECT_NE(std::count(iterations.begin(), iterations.end(), std::to_string(kBudget + 1)), 0);
  const auto solved = column(unsplit / "benchmark.db", "solved");
  EXPECT_NE(std::count(solved.begin(), solved.end(), "1"), 0);
  EXPECT_NE(std::count(solved.begin(), solved.end(), "0"), 0);

  // Recorded where a reader of the results finds it: campaign.json and every log (experiment parameter).
  const auto settings = nlohmann::json::parse(readFile(unsplit / "campaign.json"));
  EXPECT_EQ(settings.at("iteration_budget").get<unsigned>(), kBudget);
  for (const auto& budget :
       column(unsplit / "benchmark.db", "(SELECT iterationbudget FROM experiments e WHERE e.id = experimentid)")) {
    EXPECT_EQ(budget, std::to_string(kBudget));
  }
  for (const auto& log : filesBelow(unsplit / "logs", ".log")) {
    EXPECT_NE(readFile(log).find("\niteration budget INTEGER = 2000\n"), std::string::npos) << log;
  }

  // Another budget is another campaign: resuming with it is refused.
  const auto other = runArcplan(benchArguments(suite, unsplit, {"--budget", "3000"}));
  EXPECT_EQ(other.exitCode, 1);
  EXPECT_NE(other.err.find("(iteration_budget differ from campaign.json)"), std::string::npos) << other.err;

  // A campaign from before the run seeds were one per problem (no "seeding" in campaign.json) is not
  // resumed: its finished jobs drew from other seeds than the rest would.
  auto before = settings;
  before.erase("seeding");
  std::ofstream(unsplit / "campaign.json") << before.dump(2) << "\n";
  const auto resumed = runArcplan(benchArguments(suite, unsplit, {"-j", "1"}));
  EXPECT_EQ(resumed.exitCode, 1);
  EXPECT_NE(resumed.err.find("(seeding differ from campaign.json)"), std::string::npos) << resumed.err;
}

TEST(CampaignDeterminism, BudgetOptionAndSuiteFieldAreChecked) {
  const auto dir = freshTempDirectory("determinism_input");
  const auto suite = writeTinySuite(dir, {"arc-auto"}, 1, 10);
  for (const char* value : {"0", "-5", "1000000001", "many"}) {
    const auto result = runArcplan(benchArguments(suite, dir / "out", {"--budget", value}));
    EXPECT_EQ(result.exitCode, 2) << value << ": " << result.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << value;
  }
  std::ofstream(dir / "bad.yaml")
      << "name: bad\nbudget: 0\ngenerate: {seed: 1, line_obstacles: 1, pillars: 0, shelves: 0}\n"
         "planners: [RRT]\n";
  const auto bad = runArcplan(benchArguments(dir / "bad.yaml", dir / "out"));
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("bad.yaml:2:9: suite.budget: must be between 1 and 1000000000"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace arcplan::testing
