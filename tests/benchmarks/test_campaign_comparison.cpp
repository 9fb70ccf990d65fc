// bench compare on synthetic results (the statistical tests themselves: test_comparison_statistics.cpp): a known
// shift found, the false-alarm rate over 200 seeded no-shift pairs within a binomial bound, a 1 mm
// longer deterministic path flagged, one-sided planners reported, baselines and bad input.
#include <cmath>
#include <fstream>
#include <numeric>
#include <random>

#include <gtest/gtest.h>
#include <sqlite3.h>

#include "arcplan/benchmarks/baseline.h"
#include "arcplan/benchmarks/campaign_comparison.h"
#include "arcplan/benchmarks/comparison_statistics.h"
#include "support/command.h"
#include "support/error_message.h"

namespace arcplan::testing {
namespace {

using benchmarks::ComparisonMethod;
using benchmarks::Verdict;
using RunValues = benchmarks::RunRecord;
using Runs = benchmarks::CampaignRuns;

// ---- synthetic campaigns -----------------------------------------------------------------------

struct Stochastic {
  double successRate = 0.8;
  double scale = 1.0;  // multiplies every metric
};

// One stochastic planner's runs: metrics log-normal around fixed medians, times `scale`.
std::vector<RunValues> stochasticRuns(std::mt19937& random, int count, const Stochastic& planner) {
  std::bernoulli_distribution success(planner.successRate);
  std::lognormal_distribution<double> spread(0.0, 0.15);
  std::vector<RunValues> runs;
  for (int i = 0; i < count; ++i) {
    if (!success(random)) {
      runs.push_back({});
      continue;
    }
    runs.push_back({true,
                    {{"execution_time_s", 4.0 * planner.scale * spread(random)},
                     {"tcp_path_length_m", 1.0 * planner.scale * spread(random)},
                     {"solve_time_s", 0.2 * planner.scale * spread(random)},
                     {"min_clearance_m", 0.05 / planner.scale * spread(random)},
                     {"peak_tcp_speed_mps", 0.25 * spread(random)}}});
  }
  return runs;
}

// The arc planner: every run the same.
std::vector<RunValues> deterministicRuns(int count, double tcpLength) {
  return std::vector<RunValues>(count, RunValues{true,
                                                 {{"execution_time_s", 4.17},
                                                  {"tcp_path_length_m", tcpLength},
                                                  {"min_clearance_m", 0.0946},
                                                  {"peak_tcp_speed_mps", 0.25}}});
}

benchmarks::CampaignResults campaign(const std::string& name, const Runs& runs) {
  return benchmarks::campaignResultsFromRuns(name, runs);
}

const benchmarks::ComparisonRow& rowOf(const benchmarks::CampaignComparison& comparison, const std::string& planner,
                                       const std::string& metric) {
  for (const auto& row : comparison.rows) {
    if (row.planner == planner && row.metric == metric) return row;
  }
  throw std::runtime_error("no row " + planner + " " + metric);
}

TEST(CampaignComparison, AKnownShiftOfAStochasticPlannerIsFlaggedBothWays) {
  std::mt19937 random(11);
  const auto base = campaign("base", {{"p", {{"RRT", stochasticRuns(random, 30, {0.9, 1.0})}}}});
  const auto slower = campaign("new", {{"p", {{"RRT", stochasticRuns(random, 30, {0.9, 1.25})}}}});
  const auto faster = campaign("new", {{"p", {{"RRT", stochasticRuns(random, 30, {0.9, 0.8})}}}});
  const auto worse = benchmarks::compareCampaigns(base, slower);
  EXPECT_TRUE(worse.anyWorse());
  const auto& time = rowOf(worse, "RRT", "execution_time_s");
  EXPECT_EQ(time.method, ComparisonMethod::MannWhitney);
  EXPECT_EQ(time.verdict, Verdict::Worse);
  EXPECT_LT(time.adjustedPValue, 0.01);
  EXPECT_GT(time.effect, 0.1);
  EXPECT_GT(time.rankBiserial, 0.5);  // most new runs slower than most base runs
  EXPECT_EQ(rowOf(worse, "RRT", "min_clearance_m").verdict, Verdict::Worse);    // clearance: higher is better
  EXPECT_EQ(rowOf(worse, "RRT", "peak_tcp_speed_mps").verdict, Verdict::Same);  // not shifted
  const auto better = benchmarks::compareCampaigns(base, faster);
  EXPECT_FALSE(better.anyWorse());
  EXPECT_EQ(rowOf(better, "RRT", "execution_time_s").verdict, Verdict::Better);
  EXPECT_EQ(rowOf(better, "RRT", "tcp_path_length_m").verdict, Verdict::Better);

  // A success rate falling from 95 % to 50 % over 40 runs: Fisher's test.
  const auto reliable = campaign("base", {{"p", {{"RRT", stochasticRuns(random, 40, {0.95, 1.0})}}}});
  const auto unreliable = campaign("new", {{"p", {{"RRT", stochasticRuns(random, 40, {0.5, 1.0})}}}});
  const auto& success = rowOf(benchmarks::compareCampaigns(reliable, unreliable), "RRT", benchmarks::kSuccessRateKey);
  EXPECT_EQ(success.method, ComparisonMethod::Fisher);
  EXPECT_EQ(success.verdict, Verdict::Worse);
}

// P(X >= k) for X ~ Binomial(n, p), summed term by term (log-gamma binomial coefficients).
double binomialUpperTail(int n, double p, int k) {
  double tail = 0.0;
  for (int i = k; i <= n; ++i) {
    const double logChoose = std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0);
    tail += std::exp(logChoose + i * std::log(p) + (n - i) * std::log1p(-p));
  }
  return tail;
}

// The smallest k with P(X > k) <= 0.001: more false alarms than that would be a calibration error, not bad luck.
int falseAlarmBound(int n, double p) {
  int k = 0;
  while (binomialUpperTail(n, p, k + 1) > 0.001) ++k;
  return k;
}

TEST(CampaignComparison, WithoutAShiftFalseAlarmsStayWithinTheBinomialBoundOfAlpha) {
  constexpr int kPairs = 200;
  // Without a minimum effect the verdicts rest on the p-values alone: Holm keeps the chance of any
  // alarm in a table (six tests here) at most alpha, so the alarms over 200 independent tables are
  // at most Binomial(200, alpha).
  for (const double alpha : {0.05, 0.01}) {
    benchmarks::ComparisonOptions options;
    options.alpha = alpha;
    options.minEffect = 0.0;
    options.solveTimeFloor = 0.0;
    int alarms = 0, tested = 0;
    for (int seed = 0; seed < kPairs; ++seed) {
      std::mt19937 random(static_cast<unsigned>(1000 + seed));
      const auto base = campaign("base", {{"p", {{"RRT", stochasticRuns(random, 20, {})}}}});
      const auto current = campaign("new", {{"p", {{"RRT", stochasticRuns(random, 20, {})}}}});
      const auto comparison = benchmarks::compareCampaigns(base, current, options);
      alarms += comparison.count(Verdict::Worse) + comparison.count(Verdict::Better) > 0;
      tested += rowOf(comparison, "RRT", "execution_time_s").method == ComparisonMethod::MannWhitney;
    }
    EXPECT_EQ(tested, kPairs);
    EXPECT_LE(alarms, falseAlarmBound(kPairs, alpha)) << "alpha " << alpha;
  }
  // With the defaults (alpha 0.01, minimum effect 5 %) no-shift pairs raise even fewer alarms.
  int alarms = 0;
  for (int seed = 0; seed < kPairs; ++seed) {
    std::mt19937 random(static_cast<unsigned>(5000 + seed));
    const auto base = campaign("base", {{"p", {{"RRT", stochasticRuns(random, 20, {})}}}});
    const auto current = campaign("new", {{"p", {{"RRT", stochasticRuns(random, 20, {})}}}});
    alarms += benchmarks::compareCampaigns(base, current).anyWorse();
  }
  EXPECT_LE(alarms, falseAlarmBound(kPairs, 0.01));
}

void writeMedianRun(const std::filesystem::path& file, double zShiftFromWaypoint3) {
  std::ofstream out(file);
  out << "# planner: arc-h1.00r\nt,tcp_speed,x,y,z,q0,q1,q2,q3,q4,q5\n";
  for (int i = 0; i < 6; ++i) {
    const double z = 0.25 + 0.01 * i + (i >= 3 ? zShiftFromWaypoint3 : 0.0);
    out << 0.1 * i << ",0.2,0.4," << -0.4 + 0.01 * i << "," << z << ",-1.09,-1.51,2.35,-2.41,-1.57,-1.09\n";
  }
}

TEST(CampaignComparison, ADeterministicPathOneMillimetreLongerIsFlaggedWithItsFirstDifferingWaypoint) {
  auto base = campaign("base", {{"thesis/obstacle", {{"arc-h1.00r", deterministicRuns(10, 0.992038)}}}});
  auto longer = campaign("new", {{"thesis/obstacle", {{"arc-h1.00r", deterministicRuns(10, 0.993038)}}}});
  const auto directory = freshTempDirectory("comparison_paths");
  writeMedianRun(directory / "base.csv", 0.0);
  writeMedianRun(directory / "new.csv", 0.001);
  base.problems["thesis/obstacle"]["arc-h1.00r"].medianRun = directory / "base.csv";
  longer.problems["thesis/obstacle"]["arc-h1.00r"].medianRun = directory / "new.csv";

  const auto comparison = benchmarks::compareCampaigns(base, longer);
  EXPECT_TRUE(comparison.anyWorse());
  const auto& length = rowOf(comparison, "arc-h1.00r", "tcp_path_length_m");
  EXPECT_EQ(length.method, ComparisonMethod::Exact);
  EXPECT_EQ(length.verdict, Verdict::Worse);
  EXPECT_NEAR(length.current - length.base, 0.001, 1e-12);
  EXPECT_NE(length.note.find("waypoint 3: z 0.28 -> 0.281"), std::string::npos) << length.note;
  EXPECT_EQ(rowOf(comparison, "arc-h1.00r", "execution_time_s").verdict, Verdict::Same);
  EXPECT_EQ(rowOf(comparison, "arc-h1.00r", benchmarks::kSuccessRateKey).method, ComparisonMethod::Exact);
  // Below the tolerance (1e-6 m) the same path is the same.
  const auto tiny = campaign("new", {{"thesis/obstacle", {{"arc-h1.00r", deterministicRuns(10, 0.992038 + 5e-7)}}}});
  EXPECT_FALSE(benchmarks::compareCampaigns(base, tiny).anyWorse());
  // A deterministic planner that stops solving is worse in its success rate.
  const auto failing = campaign("new", {{"thesis/obstacle", {{"arc-h1.00r", std::vector<RunValues>(10)}}}});
  const auto failed = benchmarks::compareCampaigns(base, failing);
  EXPECT_EQ(rowOf(failed, "arc-h1.00r", benchmarks::kSuccessRateKey).verdict, Verdict::Worse);
  EXPECT_EQ(rowOf(failed, "arc-h1.00r", "tcp_path_length_m").verdict, Verdict::NotComparable);
}

TEST(CampaignComparison, APlannerOnOneSideOnlyIsReportedAndDifferentSettingsAreListed) {
  std::mt19937 random(3);
  Runs baseRuns{{"p", {{"RRT", stochasticRuns(random, 10, {})}, {"arc", deterministicRuns(10, 1.0)}}}};
  Runs newRuns{{"p", {{"arc", deterministicRuns(11, 1.0)}, {"PRM", stochasticRuns(random, 10, {})}}}};
  const auto base = benchmarks::campaignResultsFromRuns(
      "base", baseRuns, {{"p", {{"arc", {{"runs", "10"}, {"OMPL version", "1.5.2"}}}, {"RRT", {{"runs", "10"}}}}}});
  const auto current = benchmarks::campaignResultsFromRuns(
      "new", newRuns, {{"p", {{"arc", {{"runs", "11"}, {"OMPL version", "1.5.2"}}}, {"PRM", {{"runs", "10"}}}}}});
  const auto comparison = benchmarks::compareCampaigns(base, current);
  EXPECT_EQ(comparison.onlyInBase, std::vector<std::string>{"p · RRT"});
  EXPECT_EQ(comparison.onlyInNew, std::vector<std::string>{"p · PRM"});
  EXPECT_EQ(rowOf(comparison, "RRT", "-").verdict, Verdict::NotComparable);
  EXPECT_FALSE(comparison.anyWorse());
  EXPECT_EQ(rowOf(comparison, "arc", "execution_time_s").verdict, Verdict::Same);  // still compared
  ASSERT_EQ(comparison.settings.size(), 1u);
  EXPECT_EQ(comparison.settings[0].setting, "runs");
  EXPECT_EQ(comparison.settings[0].base, "10");
  EXPECT_EQ(comparison.settings[0].current, "11");
  EXPECT_TRUE(comparison.settings[0].pairs.empty());  // the only matched pair: "every pair"
  const auto markdown = benchmarks::comparisonMarkdown(comparison);
  EXPECT_LT(markdown.find("only in base: p · RRT"), markdown.find("## Results"));
  EXPECT_LT(markdown.find("| runs | 10 | 11 | every pair |"), markdown.find("## Results"));
  EXPECT_NE(benchmarks::comparisonCsv(comparison).find("p,RRT,-,-,10,0,,,,,,not comparable,only in base\n"),
            std::string::npos);
  EXPECT_EQ(benchmarks::comparisonJson(comparison)["counts"]["worse"], 0);
}

TEST(CampaignComparison, OptionsOutOfRangeAndUnknownMetricsAreRefused) {
  benchmarks::ComparisonOptions options;
  options.alpha = 1.5;
  EXPECT_NE(errorMessageOf([&] { benchmarks::checkComparisonOptions(options); }).find("--alpha"), std::string::npos);
  options = {};
  options.metrics = {"speediness"};
  EXPECT_NE(errorMessageOf([&] { benchmarks::checkComparisonOptions(options); }).find("'speediness'"),
            std::string::npos);
}

// ---- campaign folders, databases and baselines on disk -----------------------------------------

void execute(sqlite3* db, const std::string& sql) {
  char* message = nullptr;
  ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message), SQLITE_OK) << (message ? message : "") << sql;
}

// A campaign folder as `arcplan bench` leaves it, with the tables ompl_benchmark_statistics makes
// (the columns the comparison reads): arc deterministic, RRT stochastic, 12 runs each.
std::filesystem::path syntheticCampaign(const std::string& name, double arcLength) {
  const auto directory = freshTempDirectory(name);
  std::ofstream(directory / "campaign.json")
      << R"({"suite": "thesis", "runs": 12, "time_limit_s": 1.0, "vmax_mps": 0.25, "generator_seed": null,)"
      << R"( "problems": ["obstacle"], "planners": [{"name": "arc", "planner": "arc", "params": {}},)"
      << R"( {"name": "RRT", "planner": "RRT", "params": {}}]})";
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open((directory / "benchmark.db").c_str(), &db), SQLITE_OK);
  execute(db,
          "CREATE TABLE experiments (id INTEGER PRIMARY KEY, name VARCHAR(512), timelimit REAL, runcount INTEGER,"
          " vmax REAL, omplversion TEXT)");
  execute(db, "CREATE TABLE plannerConfigs (id INTEGER PRIMARY KEY, name VARCHAR(512) NOT NULL, settings TEXT)");
  execute(db,
          "CREATE TABLE runs (id INTEGER PRIMARY KEY, experimentid INTEGER, plannerid INTEGER, solved BOOLEAN,"
          " execution_time REAL, tcp_path_length REAL, solve_time REAL, min_clearance REAL, peak_tcp_speed REAL)");
  execute(db,
          "INSERT INTO experiments VALUES (1, 'thesis/obstacle', 1.0, 12, 0.25, '1.5.2'),"
          " (2, 'thesis/obstacle', 1.0, 12, 0.25, '1.5.2')");
  execute(db,
          "INSERT INTO plannerConfigs VALUES (1, 'geometric_arc', 'sagitta = 0.2\n;projection.cellsize.0 = 0.07\n;'),"
          " (2, 'geometric_RRT', 'range = 5.7\n;')");
  std::mt19937 random(5);
  std::lognormal_distribution<double> spread(0.0, 0.2);
  for (int run = 0; run < 12; ++run) {
    execute(db,
            "INSERT INTO runs (experimentid, plannerid, solved, execution_time, tcp_path_length, solve_time,"
            " min_clearance, peak_tcp_speed) VALUES (1, 1, 1, 4.17, " +
                std::to_string(arcLength) + ", " + std::to_string(0.0004 * spread(random)) + ", 0.0946, 0.25)");
    const bool solved = run % 4 != 0;
    execute(db,
            "INSERT INTO runs (experimentid, plannerid, solved, execution_time, tcp_path_length, solve_time,"
            " min_clearance, peak_tcp_speed) VALUES (2, 2, " +
                std::string(solved ? "1, " : "0, NULL, NULL, NULL, NULL, NULL)") +
                (solved ? std::to_string(5 * spread(random)) + ", " + std::to_string(1.2 * spread(random)) + ", " +
                              std::to_string(0.1 * spread(random)) + ", " + std::to_string(0.05 * spread(random)) +
                              ", 0.25)"
                        : std::string()));
  }
  sqlite3_close(db);
  return directory;
}

TEST(CampaignComparison, ACampaignFolderReadsRunsAndSettingsFromItsDatabase) {
  const auto folder = syntheticCampaign("comparison_folder", 0.992038);
  const auto results = benchmarks::loadCampaignResults(folder);
  const auto& arc = results.problems.at("thesis/obstacle").at("arc");
  EXPECT_EQ(arc.runs, 12);
  EXPECT_EQ(arc.successes, 12);
  EXPECT_EQ(arc.values.at("tcp_path_length_m"), std::vector<double>(12, 0.992038));
  EXPECT_EQ(arc.settings.at("parameter sagitta"), "0.2");
  EXPECT_EQ(arc.settings.count("parameter projection.cellsize.0"), 0u);  // random per job in OMPL: not a setting
  EXPECT_EQ(arc.settings.at("runs"), "12");
  EXPECT_EQ(arc.settings.at("OMPL version"), "1.5.2");
  const auto& rrt = results.problems.at("thesis/obstacle").at("RRT");
  EXPECT_EQ(rrt.successes, 9);
  EXPECT_EQ(rrt.values.at("execution_time_s").size(), 9u);
  // The database file itself reads the same runs.
  EXPECT_EQ(benchmarks::loadCampaignResults(folder / "benchmark.db").problems.at("thesis/obstacle").at("RRT").successes,
            9);
  EXPECT_FALSE(benchmarks::compareCampaigns(results, results).anyWorse());
}

TEST(CampaignComparison, ABaselineKeepsExactValuesAndDistributionsAndComparesLikeItsCampaign) {
  const auto folder = syntheticCampaign("comparison_baseline", 0.992038);
  const auto baseline = benchmarks::makeBaseline(folder);
  const auto file = folder / "baseline.json";
  std::ofstream(file) << baseline.dump(1);
  const auto read = benchmarks::readBaseline(file);
  EXPECT_EQ(read["campaign"]["suite"], "thesis");
  const auto& results = read["results"];
  ASSERT_EQ(results.size(), 2u);
  const auto& arc = results[1]["planner"] == "arc" ? results[1] : results[0];
  const auto& rrt = results[1]["planner"] == "arc" ? results[0] : results[1];
  EXPECT_DOUBLE_EQ(arc["metrics"]["tcp_path_length_m"]["value"].get<double>(), 0.992038);
  EXPECT_EQ(arc["metrics"]["tcp_path_length_m"]["count"], 12);
  EXPECT_EQ(rrt["metrics"]["execution_time_s"]["quantiles"].size(), 21u);
  EXPECT_EQ(rrt["successes"], 9);

  // The baseline against its own campaign: nothing differs; against a 1 mm longer arc: worse.
  const auto fromBaseline = benchmarks::loadCampaignResults(file);
  EXPECT_EQ(fromBaseline.problems.at("thesis/obstacle").at("RRT").values.at("execution_time_s").size(), 9u);
  const auto same = benchmarks::compareCampaigns(fromBaseline, benchmarks::loadCampaignResults(folder));
  EXPECT_EQ(same.count(Verdict::Worse) + same.count(Verdict::Better), 0) << benchmarks::comparisonMarkdown(same);
  EXPECT_TRUE(same.settings.empty());
  const auto longer = syntheticCampaign("comparison_baseline_longer", 0.993038);
  const auto worse = benchmarks::compareCampaigns(fromBaseline, benchmarks::loadCampaignResults(longer));
  EXPECT_EQ(rowOf(worse, "arc", "tcp_path_length_m").verdict, Verdict::Worse);
}

TEST(CampaignComparison, BadInputNamesTheFileAndTheField) {
  const auto directory = freshTempDirectory("comparison_bad_input");
  const auto notCampaign = errorMessageOf([&] { benchmarks::loadCampaignResults(directory); });
  EXPECT_NE(notCampaign.find(directory.string() + ": not a finished campaign folder (no benchmark.db"),
            std::string::npos)
      << notCampaign;
  std::ofstream(directory / "notes.txt") << "just text\n";
  const auto notDatabase = errorMessageOf([&] { benchmarks::loadCampaignResults(directory / "notes.txt"); });
  EXPECT_NE(notDatabase.find((directory / "notes.txt").string()), std::string::npos) << notDatabase;
  EXPECT_NE(notDatabase.find("not an OMPL benchmark database"), std::string::npos) << notDatabase;
  EXPECT_NE(
      errorMessageOf([&] { benchmarks::loadCampaignResults(directory / "missing"); }).find("no such campaign folder"),
      std::string::npos);

  const auto folder = syntheticCampaign("comparison_bad_baseline", 1.0);
  auto baseline = benchmarks::makeBaseline(folder);
  baseline["results"][0]["metrics"]["execution_time_s"]["quantiles"][3] = -1.0;  // RRT's, now out of order
  std::ofstream(directory / "broken.json") << baseline.dump();
  const auto broken = errorMessageOf([&] { benchmarks::readBaseline(directory / "broken.json"); });
  EXPECT_NE(
      broken.find((directory / "broken.json").string() + ": results[0].metrics.execution_time_s.quantiles: expected 21 "
                                                         "finite numbers in increasing order"),
      std::string::npos)
      << broken;
  // More summarised values than runs (a count of 10^12 would otherwise be expanded into that many values).
  auto inflated = benchmarks::makeBaseline(folder);
  inflated["results"][0]["metrics"]["execution_time_s"]["count"] = 1000000000000LL;
  std::ofstream(directory / "inflated.json") << inflated.dump();
  const auto tooMany = errorMessageOf([&] { benchmarks::readBaseline(directory / "inflated.json"); });
  EXPECT_NE(tooMany.find("results[0].metrics.execution_time_s.count: expected a whole number from 1 to " +
                         inflated["results"][0]["runs"].dump()),
            std::string::npos)
      << tooMany;
  std::ofstream(directory / "truncated.json") << baseline.dump().substr(0, 100);
  EXPECT_NE(errorMessageOf([&] { benchmarks::readBaseline(directory / "truncated.json"); }).find("not valid JSON"),
            std::string::npos);
  baseline.erase("campaign");
  std::ofstream(directory / "no_campaign.json") << baseline.dump();
  EXPECT_NE(
      errorMessageOf([&] { benchmarks::readBaseline(directory / "no_campaign.json"); }).find(": campaign: expected"),
      std::string::npos);
  EXPECT_NE(errorMessageOf([&] { benchmarks::makeBaseline(directory); }).find("no campaign.json"), std::string::npos);
}

}  // namespace
}  // namespace arcplan::testing
