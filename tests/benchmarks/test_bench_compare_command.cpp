// `arcplan bench compare` and `bench baseline save|check` end to end on real thesis campaigns (small:
// a few planners, 10 runs of at most 0.5 s): a re-run of a campaign is not worse, the arc planner
// degraded under the same configuration name is, RRTConnect with 10 and 11 runs is compared with the
// different setting listed, a baseline passes its own check and flags a 1 mm longer arc path.
#include <fstream>
#include <regex>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/command.h"

namespace arcplan::testing {
namespace {

const std::filesystem::path kThesisSuite =
    std::filesystem::path(ARCPLAN_TEST_DATA_DIR) / ".." / "benchmarks" / "suites" / "thesis.yaml";

CommandResult runCampaign(const std::filesystem::path& out, const std::string& planners, const std::string& runs = "10",
                          const std::string& suite = "thesis") {
  return runArcplan({"bench", "--suite", suite, "--planners", planners, "--runs", runs, "--time", "0.5", "-j", "2",
                     "--no-plots", "--quiet", "--out", out.string()});
}

// The thesis suite with one planner configuration's parameter changed, under the same name.
std::filesystem::path suiteWithChangedParameter(const std::filesystem::path& directory, const std::string& from,
                                                const std::string& to) {
  std::string text = readFile(kThesisSuite);
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  const auto file = directory / "thesis.yaml";
  std::ofstream(file) << text;
  return file;
}

TEST(BenchCompareCommand, AThesisCampaignComparedWithARerunOfItselfHasNothingWorse) {
  const auto directory = freshTempDirectory("compare_rerun");
  const std::string planners = "arc-h1.00r,arc-h0.50r,arc-auto,RRTConnect";
  ASSERT_EQ(runCampaign(directory / "base", planners).exitCode, 0);
  ASSERT_EQ(runCampaign(directory / "rerun", planners).exitCode, 0);
  // Solve times are wall clock: on a loaded test machine two identical campaigns' millisecond medians can
  // differ by more than the default 5 ms floor. This test is about the verdicts of repeated path metrics, so
  // it asks solve time to differ by 50 ms before it counts.
  const auto result = runArcplan({"bench", "compare", (directory / "base").string(), (directory / "rerun").string(),
                                  "--out", (directory / "comparison").string(), "--solve-time-floor", "0.05"});
  EXPECT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_NE(result.out.find("- verdicts: 0 worse, 0 better, 48 same, 0 not comparable"), std::string::npos)
      << result.out;
  EXPECT_EQ(result.out.find("## Different settings"), std::string::npos) << result.out;
  for (const char* file : {"comparison.md", "comparison.json", "comparison.csv"}) {
    EXPECT_TRUE(std::filesystem::exists(directory / "comparison" / file)) << file;
  }
  const auto json = nlohmann::json::parse(readFile(directory / "comparison" / "comparison.json"));
  EXPECT_EQ(json["rows"].size(), 48u);  // 2 problems x 4 planners x (success + 5 metrics)
  for (const auto& row : json["rows"]) {
    if (row["planner"].get<std::string>().rfind("arc", 0) == 0 && row["metric"] != "solve_time_s") {
      EXPECT_EQ(row["test"], "exact") << row;  // the arc planner repeats itself exactly
    }
  }
}

TEST(BenchCompareCommand, TheArcPlannerDegradedUnderTheSameNameIsFlaggedWithExitCode1) {
  const auto directory = freshTempDirectory("compare_degraded");
  ASSERT_EQ(runCampaign(directory / "base", "arc-h0.50r,RRTConnect").exitCode, 0);
  // A larger sagitta makes arc-h0.50r's detour around the obstacle longer.
  const auto degraded = suiteWithChangedParameter(directory, "{name: arc-h0.50r, planner: arc, params: {sagitta: 0.1,",
                                                  "{name: arc-h0.50r, planner: arc, params: {sagitta: 0.12,");
  ASSERT_EQ(runCampaign(directory / "new", "arc-h0.50r", "10", degraded.string()).exitCode, 0);
  const auto result = runArcplan({"bench", "compare", (directory / "base").string(), (directory / "new").string()});
  EXPECT_EQ(result.exitCode, 1) << result.out << result.err;
  EXPECT_NE(result.err.find("bench: 2 result(s) worse than the base"), std::string::npos) << result.err;
  const auto& out = result.out;
  // One-sided pairs and the changed parameter come before the results.
  const auto results = out.find("## Results");
  EXPECT_LT(out.find("- only in base: thesis/obstacle · RRTConnect"), results) << out;
  EXPECT_LT(out.find("| parameter sagitta | 0.1 | 0.12 | every pair |"), results) << out;
  EXPECT_TRUE(
      std::regex_search(out, std::regex(R"(\| thesis/obstacle \| arc-h0\.50r \| TCP path length \(m\) \| 10 → 10 \| )"
                                        R"([0-9.]+ \| [0-9.]+ \| \+[0-9.]+ % \| exact \| - \| - \| \*\*worse\*\* \| )"
                                        R"(median runs first differ at waypoint [0-9]+: [xyzq][0-5]? )")))
      << out;
  // The straight case has no obstacle to detour around: the same path.
  EXPECT_EQ(out.find("| thesis/straight | arc-h0.50r | TCP path length"), std::string::npos) << out;
}

TEST(BenchCompareCommand, RrtConnectWithTenAndElevenRunsIsComparedWithTheDifferentSettingListed) {
  const auto directory = freshTempDirectory("compare_runs");
  ASSERT_EQ(runCampaign(directory / "ten", "RRTConnect", "10").exitCode, 0);
  ASSERT_EQ(runCampaign(directory / "eleven", "RRTConnect", "11").exitCode, 0);
  const auto result =
      runArcplan({"bench", "compare", (directory / "ten").string(), (directory / "eleven").string(), "--all"});
  EXPECT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_NE(result.out.find("| runs | 10 | 11 | every pair |"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("| thesis/obstacle | RRTConnect | success rate | 10 → 11 |"), std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("0 worse"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("0 not comparable"), std::string::npos) << result.out;
}

TEST(BenchCompareCommand, ABaselinePassesItsOwnCheckAndFlagsAOneMillimetreLongerArcPath) {
  const auto directory = freshTempDirectory("compare_baseline");
  ASSERT_EQ(runCampaign(directory / "base", "arc-h1.00r,RRTConnect").exitCode, 0);
  const auto baseline = directory / "baseline.json";
  const auto save = runArcplan({"bench", "baseline", "save", (directory / "base").string(), baseline.string()});
  ASSERT_EQ(save.exitCode, 0) << save.err;

  const auto check = runArcplan({"bench", "baseline", "check", baseline.string(), "-j", "2", "--quiet"});
  EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
  EXPECT_NE(check.out.find("- new: `re-run of " + baseline.string() + "`"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("0 worse"), std::string::npos) << check.out;

  // The same campaign against a baseline whose arc path was 1 mm shorter: the new one is 1 mm longer.
  auto document = nlohmann::json::parse(readFile(baseline));
  int edited = 0;
  for (auto& result : document["results"]) {
    if (result["planner"] == "arc-h1.00r" && result["problem"] == "thesis/obstacle") {
      auto& length = result["metrics"]["tcp_path_length_m"];
      ASSERT_TRUE(length.contains("value")) << length;  // deterministic: kept exactly
      length["value"] = length["value"].get<double>() - 0.001;
      ++edited;
    }
  }
  ASSERT_EQ(edited, 1);
  const auto shorter = directory / "shorter.json";
  std::ofstream(shorter) << document.dump(1);
  const auto flagged = runArcplan({"bench", "compare", shorter.string(), (directory / "base").string()});
  EXPECT_EQ(flagged.exitCode, 1) << flagged.out << flagged.err;
  EXPECT_TRUE(
      std::regex_search(flagged.out, std::regex(R"(\| thesis/obstacle \| arc-h1\.00r \| TCP path length \(m\) \| .*)"
                                                R"(\| exact \| - \| - \| \*\*worse\*\* \|)")))
      << flagged.out;
}

TEST(BenchCompareCommand, BadInputExitsWith1AndAWrongCommandLineWith2) {
  const auto directory = freshTempDirectory("compare_bad_input");
  const auto missing = runArcplan({"bench", "compare", (directory / "nothing").string(), directory.string()});
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.err.find("arcplan: error: " + (directory / "nothing").string() + ": no such campaign folder"),
            std::string::npos)
      << missing.err;
  const auto notCampaign = runArcplan({"bench", "compare", directory.string(), directory.string()});
  EXPECT_EQ(notCampaign.exitCode, 1);
  EXPECT_NE(notCampaign.err.find("not a finished campaign folder"), std::string::npos) << notCampaign.err;
  std::ofstream(directory / "broken.json") << R"({"format": "arcplan benchmark baseline", "version": 1})";
  const auto broken = runArcplan({"bench", "baseline", "check", (directory / "broken.json").string()});
  EXPECT_EQ(broken.exitCode, 1);
  EXPECT_NE(broken.err.find((directory / "broken.json").string() + ": campaign: expected this field"),
            std::string::npos)
      << broken.err;
  EXPECT_EQ(runArcplan({"bench", "compare", directory.string()}).exitCode, 2);
  const auto alpha = runArcplan({"bench", "compare", directory.string(), directory.string(), "--alpha", "2"});
  EXPECT_EQ(alpha.exitCode, 2);
  EXPECT_NE(alpha.err.find("--alpha must be in (0, 1)"), std::string::npos) << alpha.err;
  EXPECT_EQ(runArcplan({"bench", "compare", directory.string(), directory.string(), "--metrics", "speed"}).exitCode, 2);
  // The same --workers rule as `bench` (apps/cli_support.h), checked before the baseline is read.
  const auto noWorkers = runArcplan({"bench", "baseline", "check", (directory / "broken.json").string(), "-j", "0"});
  EXPECT_EQ(noWorkers.exitCode, 2);
  EXPECT_NE(noWorkers.err.find("--workers must be at least 1"), std::string::npos) << noWorkers.err;
  EXPECT_EQ(runArcplan({"bench", "baseline"}).exitCode, 2);
  EXPECT_EQ(runArcplan({"bench", "compare", "--help"}).exitCode, 0);
}

}  // namespace
}  // namespace arcplan::testing
