// The comparison page's data (bench compare --html): every row and setting of the comparison, each
// side's run values per planner for the box plots, the metric labels and directions; the page
// written as one file with the comparison script inlined.
#include <gtest/gtest.h>

#include "arcplan/report/comparison_report.h"
#include "support/command.h"

namespace {

using RunValues = arcplan::benchmarks::RunRecord;

std::vector<RunValues> runs(std::initializer_list<double> lengths) {
  std::vector<RunValues> result;
  for (double length : lengths)
    result.push_back({true, {{"execution_time_s", 4 * length}, {"tcp_path_length_m", length}}});
  result.push_back({});  // one failed run
  return result;
}

TEST(ComparisonReport, DataHoldsTheRowsAndEachSidesRunsPerPlanner) {
  const auto base = arcplan::benchmarks::campaignResultsFromRuns(
      "base", {{"p", {{"RRT", runs({1.0, 1.1, 1.2})}, {"PRM", runs({2.0})}}}}, {{"p", {{"RRT", {{"runs", "4"}}}}}});
  const auto current = arcplan::benchmarks::campaignResultsFromRuns("new", {{"p", {{"RRT", runs({1.3, 1.4})}}}},
                                                                    {{"p", {{"RRT", {{"runs", "3"}}}}}});
  arcplan::benchmarks::ComparisonOptions options;
  options.metrics = {"tcp_path_length_m", "min_clearance_m"};
  const auto comparison = arcplan::benchmarks::compareCampaigns(base, current, options);
  const auto data = arcplan::report::comparisonReportData(comparison, base, current);

  EXPECT_EQ(data["comparison"]["rows"].size(), 4u);  // RRT: success + 2 metrics; PRM: only in base
  EXPECT_EQ(data["comparison"]["only_in_base"], nlohmann::json::array({"p · PRM"}));
  EXPECT_EQ(data["comparison"]["settings"][0]["setting"], "runs");
  ASSERT_EQ(data["metrics"].size(), 2u);
  EXPECT_EQ(data["metrics"][0]["label"], "TCP path length (m)");
  EXPECT_EQ(data["metrics"][0]["lower_is_better"], true);
  EXPECT_EQ(data["metrics"][1]["lower_is_better"], false);  // clearance: higher is better
  const auto& rrt = data["values"]["p"]["RRT"];
  EXPECT_EQ(rrt["base"]["runs"], 4);
  EXPECT_EQ(rrt["base"]["successes"], 3);
  EXPECT_EQ(rrt["base"]["tcp_path_length_m"], nlohmann::json::array({1.0, 1.1, 1.2}));
  EXPECT_EQ(rrt["new"]["tcp_path_length_m"], nlohmann::json::array({1.3, 1.4}));
  EXPECT_TRUE(rrt["new"]["min_clearance_m"].empty());  // not measured
  EXPECT_FALSE(data["values"]["p"]["PRM"].contains("new"));
  EXPECT_EQ(data["missing"].size(), 1u);

  const auto file = arcplan::testing::freshTempDirectory("comparison_report") / "comparison.html";
  arcplan::report::writeComparisonReport(file, comparison, base, current);
  const auto page = arcplan::testing::readFile(file);
  EXPECT_NE(page.find("<title>arcplan campaign comparison — base vs new</title>"), std::string::npos);
  EXPECT_NE(page.find("<script data-name=\"comparison.js\">"), std::string::npos);
  EXPECT_NE(page.find("<script data-name=\"plotly.js\">"), std::string::npos);
  EXPECT_EQ(page.find("<script data-name=\"three.js\">"), std::string::npos);  // no 3D view on this page
}

}  // namespace
