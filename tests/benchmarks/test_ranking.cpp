// The ranking rules on hand-made run data: success rate first, then the median execution time over
// all runs with failures as +inf, shared ranks for ties, mean rank across problems.
#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include "arcplan/benchmarks/ranking.h"

namespace arcplan::benchmarks {
namespace {

using RunValues = RunRecord;
using Runs = CampaignRuns;

RunValues success(double executionTime, double tcpLength = 1.0) {
  return {true, {{"execution_time_s", executionTime}, {"tcp_path_length_m", tcpLength}, {"solve_time_s", 0.01}}};
}
RunValues failure() { return {}; }

std::vector<RunValues> runs(int successes, int failures, double executionTime, double tcpLength = 1.0) {
  std::vector<RunValues> result;
  for (int i = 0; i < successes; ++i) result.push_back(success(executionTime + 0.001 * i, tcpLength));
  for (int i = 0; i < failures; ++i) result.push_back(failure());
  return result;
}

const PlannerStanding& standing(const std::vector<PlannerStanding>& standings, const std::string& planner) {
  for (const auto& s : standings) {
    if (s.planner == planner) return s;
  }
  throw std::runtime_error("no planner " + planner);
}

TEST(Ranking, RareSuccessDoesNotWinOnItsMedian) {
  // "lucky" solves 2 of 100 runs, very fast; "steady" solves all 100, slower.
  Runs data;
  data["p"]["lucky"] = runs(2, 98, 1.0);
  data["p"]["steady"] = runs(100, 0, 5.0);
  const auto ranking = rankRuns(data);
  ASSERT_EQ(ranking.problems.size(), 1u);
  EXPECT_EQ(ranking.problems[0].planners[0].planner, "steady");
  EXPECT_EQ(standing(ranking.problems[0].planners, "steady").rank, 1);
  EXPECT_EQ(standing(ranking.problems[0].planners, "lucky").rank, 2);
  // Its median over all runs, failures as +inf, is +inf; its metric median over the 2 successes is 1.0005.
  EXPECT_TRUE(std::isinf(standing(ranking.problems[0].planners, "lucky").medianExecutionTime));
  EXPECT_NEAR(standing(ranking.problems[0].planners, "lucky").metrics.at("execution_time_s").median, 1.0005, 1e-12);
  EXPECT_DOUBLE_EQ(standing(ranking.problems[0].planners, "lucky").successRate, 0.02);
}

TEST(Ranking, FailuresCountAsInfiniteInTheMedianOfAllRuns) {
  Runs data;
  data["p"]["six"] = runs(6, 4, 2.0);   // sorted: 2.000 .. 2.005, inf x4 -> median (2.004 + 2.005) / 2
  data["p"]["five"] = runs(5, 5, 1.0);  // median of 10 with 5 inf: (1.004 + inf) / 2 = inf
  data["p"]["seven"] =
      runs(7, 3, 3.0);  // median: (3.004 + 3.005) / 2... of 3.000..3.006 and 3 inf: 5th,6th = 3.004, 3.005
  const auto ranking = rankRuns(data);
  const auto& planners = ranking.problems[0].planners;
  EXPECT_NEAR(standing(planners, "six").medianExecutionTime, 2.0045, 1e-12);
  EXPECT_TRUE(std::isinf(standing(planners, "five").medianExecutionTime));
  EXPECT_NEAR(standing(planners, "seven").medianExecutionTime, 3.0045, 1e-12);
  // Success rate first: seven (70 %) > six (60 %) > five (50 %), whatever the times.
  EXPECT_EQ(planners[0].planner, "seven");
  EXPECT_EQ(planners[1].planner, "six");
  EXPECT_EQ(planners[2].planner, "five");
}

TEST(Ranking, EqualSuccessIsDecidedByTheMedianExecutionTime) {
  Runs data;
  data["p"]["slow"] = runs(10, 0, 4.0);
  data["p"]["fast"] = runs(10, 0, 3.0);
  const auto ranking = rankRuns(data);
  const auto& planners = ranking.problems[0].planners;
  EXPECT_EQ(planners[0].planner, "fast");
  EXPECT_EQ(planners[0].rank, 1);
  EXPECT_EQ(planners[1].rank, 2);
}

TEST(Ranking, TiesShareARankAndTheNextRankSkips) {
  Runs data;
  data["p"]["arc-a"] = std::vector<RunValues>(5, success(3.5, 0.9));
  data["p"]["arc-b"] = std::vector<RunValues>(5, success(3.5, 0.8));  // same key, shorter path: listed first
  data["p"]["rrt"] = std::vector<RunValues>(5, success(3.9));
  data["p"]["never"] = runs(0, 5, 0.0);
  data["p"]["none"] = runs(0, 5, 0.0);
  const auto ranking = rankRuns(data);
  const auto& planners = ranking.problems[0].planners;
  ASSERT_EQ(planners.size(), 5u);
  EXPECT_EQ(planners[0].planner, "arc-b");
  EXPECT_EQ(planners[1].planner, "arc-a");
  EXPECT_EQ(planners[0].rank, 1);
  EXPECT_EQ(planners[1].rank, 1);
  EXPECT_EQ(planners[2].rank, 3);
  // Planners without a success share the last rank.
  EXPECT_EQ(standing(planners, "never").rank, 4);
  EXPECT_EQ(standing(planners, "none").rank, 4);
}

TEST(Ranking, MetricSummariesUseSuccessfulRunsOnly) {
  Runs data;
  data["p"]["x"] = {success(4.0, 1.0), failure(), success(2.0, 3.0), success(3.0, 2.0), success(5.0, 4.0)};
  const auto ranking = rankRuns(data);
  const auto& x = ranking.problems[0].planners[0];
  const auto& time = x.metrics.at("execution_time_s");
  EXPECT_EQ(time.count, 4);
  EXPECT_DOUBLE_EQ(time.median, 3.5);
  EXPECT_DOUBLE_EQ(time.mean, 3.5);
  EXPECT_DOUBLE_EQ(time.min, 2.0);
  EXPECT_DOUBLE_EQ(time.max, 5.0);
  EXPECT_DOUBLE_EQ(x.metrics.at("tcp_path_length_m").median, 2.5);
  EXPECT_EQ(x.metrics.at("min_clearance_m").count, 0);  // never reported
  EXPECT_DOUBLE_EQ(x.successRate, 0.8);
}

TEST(Ranking, ASuccessIsSolvedWithAnExecutionTime) {
  RunRecord unscaled = success(1.0);  // OMPL solved it, but the path could not be time-scaled
  unscaled.values.erase("execution_time_s");
  RunRecord tooClose = success(1.0);  // scaled, but it came closer than the clearance: "solved" withdrawn
  tooClose.solved = false;
  RunRecord infinite = success(INFINITY);
  EXPECT_TRUE(success(1.0).succeeded());
  EXPECT_FALSE(unscaled.succeeded());
  EXPECT_FALSE(tooClose.succeeded());
  EXPECT_FALSE(infinite.succeeded());
  Runs data;
  data["p"]["x"] = {success(2.0), unscaled, tooClose, infinite};
  const auto ranking = rankRuns(data);
  const auto& x = ranking.problems[0].planners[0];
  EXPECT_EQ(x.successes, 1);
  EXPECT_EQ(x.metrics.at("tcp_path_length_m").count, 1);  // metrics of successful runs only
}

TEST(Ranking, OverallRankIsTheMeanRankOverProblems) {
  Runs data;
  // p1: a 1, b 2, c 3; p2: b 1, c 2, a 3; p3: b 1, a 2 (c did not run) -> a 2.0, b 1.333, c 2.5
  data["p1"]["a"] = runs(3, 0, 1.0);
  data["p1"]["b"] = runs(3, 0, 2.0);
  data["p1"]["c"] = runs(3, 0, 3.0);
  data["p2"]["b"] = runs(3, 0, 1.0);
  data["p2"]["c"] = runs(3, 0, 2.0);
  data["p2"]["a"] = runs(2, 1, 1.0);
  data["p3"]["b"] = runs(3, 0, 1.0);
  data["p3"]["a"] = runs(3, 0, 2.0);
  const auto ranking = rankRuns(data);
  ASSERT_EQ(ranking.overall.size(), 3u);
  EXPECT_EQ(ranking.overall[0].planner, "b");
  EXPECT_NEAR(ranking.overall[0].meanRank, 4.0 / 3.0, 1e-12);
  EXPECT_EQ(ranking.overall[0].firstPlaces, 2);
  EXPECT_EQ(ranking.overall[1].planner, "a");
  EXPECT_NEAR(ranking.overall[1].meanRank, 2.0, 1e-12);
  EXPECT_NEAR(ranking.overall[1].successRate, 8.0 / 9.0, 1e-12);  // pooled over its 9 runs
  EXPECT_EQ(ranking.overall[2].planner, "c");
  EXPECT_NEAR(ranking.overall[2].meanRank, 2.5, 1e-12);
  EXPECT_EQ(ranking.overall[2].problems, 2);
  EXPECT_EQ(ranking.overall[2].rank, 3);
}

TEST(Ranking, FamiliesShowWhereAPlannerLoses) {
  Runs data;
  // The arc planner wins both line problems and never solves the pillars; RRTConnect solves all.
  for (const char* line : {"line-1", "line-2"}) {
    data[line]["arc"] = runs(4, 0, 3.0);
    data[line]["rrt"] = runs(4, 0, 4.0);
  }
  for (const char* pillar : {"pillar-1", "pillar-2", "pillar-3"}) {
    data[pillar]["arc"] = runs(0, 4, 0.0);
    data[pillar]["rrt"] = runs(4, 0, 6.0);
  }
  const auto ranking = rankRuns(
      data,
      {{"line-1", "line"}, {"line-2", "line"}, {"pillar-1", "pillar"}, {"pillar-2", "pillar"}, {"pillar-3", "pillar"}});
  ASSERT_EQ(ranking.families.size(), 2u);
  const auto& line = ranking.families[0];
  const auto& pillar = ranking.families[1];
  EXPECT_EQ(line.family, "line");
  EXPECT_EQ(line.problems, 2);
  EXPECT_EQ(line.planners[0].planner, "arc");
  EXPECT_DOUBLE_EQ(line.planners[0].meanRank, 1.0);
  EXPECT_EQ(pillar.planners[0].planner, "rrt");
  EXPECT_DOUBLE_EQ(standing(pillar.planners, "arc").successRate, 0.0);
  EXPECT_DOUBLE_EQ(standing(pillar.planners, "arc").meanRank, 2.0);
  // Overall: arc (1+1+2+2+2)/5 = 1.6 behind rrt (2+2+1+1+1)/5 = 1.4.
  EXPECT_EQ(ranking.overall[0].planner, "rrt");
  EXPECT_NEAR(ranking.overall[0].meanRank, 1.4, 1e-12);
  const auto json = rankingJson(ranking);
  EXPECT_EQ(json["families"][1]["name"], "pillar");
  EXPECT_EQ(json["families"][1]["planners"][0]["name"], "rrt");
  EXPECT_NE(rankingMarkdown(ranking).find("| arc | 100 % · rank 1 | 0 % · rank 2 |"), std::string::npos)
      << rankingMarkdown(ranking);
  // Without families (or with only one) there is no family section.
  EXPECT_TRUE(rankRuns(data).families.empty());
}

TEST(Ranking, JsonListsPlannersByRankWithTheDesignKeys) {
  Runs data;
  data["p"]["slow"] = runs(4, 0, 4.0, 2.0);
  data["p"]["fast"] = runs(4, 0, 3.0, 1.0);
  const auto json = rankingJson(rankRuns(data));
  ASSERT_EQ(json["planners"].size(), 2u);
  EXPECT_EQ(json["planners"][0]["name"], "fast");
  EXPECT_EQ(json["planners"][0]["rank"], 1);
  EXPECT_EQ(json["planners"][0]["success_rate"], 1.0);
  for (const char* key :
       {"tcp_path_length_m", "joint_path_length_rad", "solve_time_s", "execution_time_s", "mean_tcp_speed_mps",
        "peak_tcp_speed_mps", "time_above_limit_s", "min_clearance_m", "max_joint_speed_ratio"}) {
    EXPECT_TRUE(json["planners"][0].contains(key)) << key;
  }
  const auto& time = json["planners"][0]["execution_time_s"];
  for (const char* statistic : {"median", "mean", "min", "max"}) EXPECT_TRUE(time.contains(statistic)) << statistic;
  EXPECT_NEAR(time["min"].get<double>(), 3.0, 1e-12);
  EXPECT_NEAR(time["max"].get<double>(), 3.003, 1e-12);
  EXPECT_TRUE(json["planners"][0]["min_clearance_m"].is_null());  // no run reported it
  EXPECT_EQ(json["problems"][0]["planners"][1]["name"], "slow");
}

TEST(Ranking, CsvHasOneRowPerPlannerAndProblemPlusOverall) {
  Runs data;
  data["p1"]["a"] = runs(2, 0, 1.0);
  data["p1"]["b"] = runs(1, 1, 2.0);
  data["p2"]["a"] = runs(2, 0, 1.0);
  const auto csv = rankingCsv(rankRuns(data));
  std::istringstream lines(csv);
  std::string header, line;
  std::getline(lines, header);
  EXPECT_EQ(header.rfind("problem,planner,rank,mean_rank,success_rate,runs,solved", 0), 0u);
  EXPECT_NE(header.find("execution_time_s_median"), std::string::npos);
  const auto columns = std::count(header.begin(), header.end(), ',');
  int rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), columns) << line;
  }
  EXPECT_EQ(rows, 2 /* overall */ + 3);
}

TEST(Ranking, MarkdownExplainsTheRules) {
  Runs data;
  data["thesis/obstacle"]["arc"] = runs(2, 0, 3.5);
  const auto markdown = rankingMarkdown(rankRuns(data));
  EXPECT_NE(markdown.find("success rate"), std::string::npos);
  EXPECT_NE(markdown.find("+inf"), std::string::npos);
  EXPECT_NE(markdown.find("mean rank"), std::string::npos);
  EXPECT_NE(markdown.find("### thesis/obstacle"), std::string::npos);
}

}  // namespace
}  // namespace arcplan::benchmarks
