// `arcplan bench` end to end: a small thesis campaign through the real OMPL Benchmark, Debian's
// ompl_benchmark_statistics and SQLite; resume, shards merged after GNU parallel, Ctrl-C, bad input.
// Over 400 lines: one campaign fixture serves every end-to-end case, and each case needs its real run.
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <map>
#include <set>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "support/command.h"
#include "support/database_rows.h"

namespace arcplan::testing {
namespace {

using Rows = std::vector<std::vector<std::string>>;

// Every row of a query, values as text ("" for NULL).
Rows query(const std::filesystem::path& database, const std::string& sql) { return databaseRows(database, sql, ""); }

std::set<std::string> columnsOf(const std::filesystem::path& database, const std::string& table) {
  std::set<std::string> columns;
  for (const auto& row : query(database, "PRAGMA table_info(" + table + ")")) columns.insert(row[1]);
  return columns;
}

const std::vector<std::string> kPlanners{"arc-h1.00r", "arc-h0.50r", "arc-auto", "RRTConnect", "PRM"};

std::vector<std::string> campaignArguments(const std::filesystem::path& out, const std::string& runs = "2") {
  return {"bench",  "--suite",    "thesis", "--planners", "arc-h1.00r,arc-h0.50r,arc-auto,RRTConnect,PRM",
          "--runs", runs,         "--time", "0.5",        "-j",
          "2",      "--no-plots", "--out",  out.string()};
}

// One small thesis campaign (5 planners x 2 problems x 2 runs), shared by the tests of one process.
struct Campaign {
  std::filesystem::path out;
  CommandResult result;
};
const Campaign& thesisCampaign() {
  static const Campaign campaign = [] {
    Campaign c;
    c.out = freshTempDirectory("bench_thesis");
    c.result = runArcplan(campaignArguments(c.out));
    return c;
  }();
  return campaign;
}

const double kStraightLength = std::sqrt(0.1 * 0.1 + 0.8 * 0.8 + 0.21 * 0.21);  // |AB| of the thesis poses

TEST(BenchCommand, ThesisCampaignWritesLogsDatabaseAndRanking) {
  const auto& campaign = thesisCampaign();
  ASSERT_EQ(campaign.result.exitCode, 0) << campaign.result.err;
  const auto logs = filesBelow(campaign.out / "logs", ".log");
  EXPECT_EQ(logs.size(), 10u);
  for (const auto& log : logs) {
    std::ifstream in(log);
    std::string first;
    std::getline(in, first);
    EXPECT_EQ(first, "OMPL version 1.5.2") << log;  // OMPL 1.5.2 itself writes an empty version
  }
  for (const char* file : {"benchmark.db", "ranking.md", "ranking.json", "ranking.csv", "campaign.json"}) {
    EXPECT_TRUE(std::filesystem::exists(campaign.out / file)) << file;
  }
  // The speed-profile and 3D plots' data: each planner's median run on the plot problems.
  for (const auto& planner : kPlanners) {
    const auto csv = readFile(campaign.out / "paths" / "thesis" / "obstacle" / (planner + ".csv"));
    EXPECT_NE(csv.find("t,tcp_speed,x,y,z,q0,q1,q2,q3,q4,q5\n"), std::string::npos) << planner;
  }
  EXPECT_TRUE(std::filesystem::exists(campaign.out / "paths" / "thesis" / "straight" / "scene.json"));
  EXPECT_FALSE(std::filesystem::exists(campaign.out / "plots"));  // --no-plots
  EXPECT_TRUE(temporaryFilesBelow(campaign.out).empty());
  // The terminal shows the ranking table and, without a terminal, one progress line per job.
  EXPECT_NE(campaign.result.out.find("| rank | planner |"), std::string::npos);
  EXPECT_NE(campaign.result.err.find("obstacle · RRTConnect: 2/2 runs solved · elapsed"), std::string::npos)
      << campaign.result.err;
  EXPECT_NE(campaign.result.err.find("ETA"), std::string::npos);
}

TEST(BenchCommand, DatabaseIsBuiltByOmplBenchmarkStatisticsFromTheLogs) {
  const auto& campaign = thesisCampaign();
  const auto db = campaign.out / "benchmark.db";
  // One experiment per (problem, planner) log, named after the problem; OMPL's real version.
  const auto experiments = query(db, "SELECT name, version, omplversion, vmax, problem, suite FROM experiments");
  ASSERT_EQ(experiments.size(), 10u);
  std::map<std::string, int> perProblem;
  for (const auto& row : experiments) {
    ++perProblem[row[0]];
    EXPECT_EQ(row[1], "OMPL 1.5.2");
    EXPECT_EQ(row[2], "1.5.2");
    EXPECT_DOUBLE_EQ(std::stod(row[3]), 0.25);
    EXPECT_EQ(row[0], "thesis/" + row[4]);
    EXPECT_EQ(row[5], "thesis");
  }
  EXPECT_EQ(perProblem["thesis/straight"], 5);
  EXPECT_EQ(perProblem["thesis/obstacle"], 5);
  // The metrics of docs/metrics.md are run properties, hence columns of the runs table.
  const auto columns = columnsOf(db, "runs");
  for (const char* column :
       {"tcp_path_length", "execution_time", "solve_time", "mean_tcp_speed", "peak_tcp_speed", "time_above_limit",
        "min_clearance", "max_joint_speed_ratio", "run_seed", "solution_length", "simplified_solution_length"}) {
    EXPECT_EQ(columns.count(column), 1u) << column;
  }
  EXPECT_EQ(query(db, "SELECT COUNT(*) FROM runs")[0][0], "20");
  // Seeds are recorded, one per problem and run (2 x 2), the same for each of the 5 planners of the
  // problem: the arc planner's fallback draws what RRTConnect draws (docs/reproducibility.md).
  EXPECT_EQ(query(db, "SELECT COUNT(DISTINCT run_seed) FROM runs")[0][0], "4");
  EXPECT_EQ(query(db,
                  "SELECT COUNT(DISTINCT e.name || '#' || r.run_seed) FROM runs r JOIN experiments e ON "
                  "r.experimentid = e.id")[0][0],
            "4");
  // Every successful run respects the speed limit.
  const auto limits =
      query(db, "SELECT MAX(peak_tcp_speed), MAX(time_above_limit) FROM runs WHERE execution_time IS NOT NULL");
  EXPECT_LE(std::stod(limits[0][0]), 0.25 + 1e-9);
  EXPECT_DOUBLE_EQ(std::stod(limits[0][1]), 0.0);
}

TEST(BenchCommand, EveryPlannerRecordsItsOwnSolveTimeBelowOmplsTime) {
  // OMPL's `time` is taken around the planner's solve, its run thread and the join of the thread that evaluates the
  // termination condition; each planner's own solve time (planners::lastSolveTime) around the solve call alone, so it
  // is positive and strictly less for every run, OMPL's planners included (they used to record OMPL's `time` itself).
  const auto rows = query(thesisCampaign().out / "benchmark.db",
                          "SELECT plannerConfigs.name, runs.solve_time, runs.time FROM runs "
                          "JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id");
  ASSERT_EQ(rows.size(), 20u);
  for (const auto& row : rows) {
    ASSERT_FALSE(row[1].empty()) << row[0];
    EXPECT_GT(std::stod(row[1]), 0.0) << row[0];
    EXPECT_LT(std::stod(row[1]), std::stod(row[2])) << row[0];
  }
}

// Per (problem, planner): runs, successes, min/max TCP length, min/max execution time.
std::map<std::pair<std::string, std::string>, std::vector<double>> statistics(const std::filesystem::path& db) {
  std::map<std::pair<std::string, std::string>, std::vector<double>> result;
  for (const auto& row : query(db,
                               "SELECT experiments.name, plannerConfigs.name, COUNT(*), "
                               "SUM(runs.solved = 1 AND runs.execution_time IS NOT NULL), MIN(tcp_path_length), "
                               "MAX(tcp_path_length), MIN(execution_time), MAX(execution_time) FROM runs "
                               "JOIN experiments ON runs.experimentid = experiments.id "
                               "JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id "
                               "GROUP BY experiments.name, plannerConfigs.name")) {
    std::vector<double> values;
    for (std::size_t i = 2; i < row.size(); ++i) values.push_back(row[i].empty() ? NAN : std::stod(row[i]));
    result[{row[0], row[1]}] = values;
  }
  return result;
}

TEST(BenchCommand, ArcPlannerSolvesTheThesisCasesDeterministically) {
  const auto stats = statistics(thesisCampaign().out / "benchmark.db");
  ASSERT_EQ(stats.size(), 10u);
  for (const char* arc : {"geometric_arc-h1.00r", "geometric_arc-h0.50r", "geometric_arc-auto"}) {
    for (const char* problem : {"thesis/straight", "thesis/obstacle"}) {
      SCOPED_TRACE(std::string(arc) + " on " + problem);
      const auto& s = stats.at({problem, arc});
      EXPECT_EQ(s[1], s[0]) << "every run succeeds";
      EXPECT_EQ(s[2], s[3]) << "zero variance in TCP path length";
      EXPECT_EQ(s[4], s[5]) << "zero variance in execution time";
    }
    // Case (a): the straight line, |AB|, in the least time of all planners: a trapezoidal speed profile
    // with rise time 0.2 s (time-scaling default) lasts |AB| / vmax + 0.2 s.
    // Between its IK waypoints (1 cm apart) the path is joint-linear, so the TCP bows off the line by
    // about 0.1 mm: the length exceeds |AB| by 0.03 %, where any detour would add centimetres.
    const auto& straight = stats.at({"thesis/straight", arc});
    EXPECT_GE(straight[2], kStraightLength - 1e-9);
    EXPECT_LE(straight[2], kStraightLength + 5e-4);
    EXPECT_NEAR(straight[4], kStraightLength / 0.25 + 0.2, 0.01 * (kStraightLength / 0.25 + 0.2));
    for (const auto& [key, other] : stats) {
      if (key.first != "thesis/straight") continue;
      EXPECT_LE(straight[4], other[4] + 1e-9) << key.second;
    }
  }
  // Case (b): the densely sampled arc path converges to the analytic lengths of docs/planners.md (a polyline
  // through points of an arc is slightly shorter).
  for (const auto& [arc, analytic] : {std::pair{"geometric_arc-h1.00r", 0.9920}, {"geometric_arc-h0.50r", 0.8825}}) {
    const double length = stats.at({"thesis/obstacle", arc})[2];
    EXPECT_LE(length, analytic * 1.0005) << arc;
    EXPECT_GE(length, analytic * 0.995) << arc;
  }
}

TEST(BenchCommand, RankingAgreesWithTheDatabase) {
  const auto& campaign = thesisCampaign();
  const auto ranking = nlohmann::json::parse(readFile(campaign.out / "ranking.json"));
  const auto stats = statistics(campaign.out / "benchmark.db");
  ASSERT_EQ(ranking["planners"].size(), kPlanners.size());
  int previousRank = 0;
  for (const auto& planner : ranking["planners"]) {
    EXPECT_GE(planner["rank"].get<int>(), previousRank);
    previousRank = planner["rank"].get<int>();
    double runs = 0, successes = 0;
    for (const auto& [key, s] : stats) {
      if (key.second == "geometric_" + planner["name"].get<std::string>()) {
        runs += s[0];
        successes += s[1];
      }
    }
    EXPECT_DOUBLE_EQ(planner["success_rate"].get<double>(), successes / runs) << planner["name"];
  }
  // On the straight case every arc configuration returns the same line: one shared first rank.
  for (const auto& problem : ranking["problems"]) {
    if (problem["name"] != "thesis/straight") continue;
    for (const auto& planner : problem["planners"]) {
      const auto name = planner["name"].get<std::string>();
      if (name.rfind("arc", 0) == 0) {
        EXPECT_EQ(planner["rank"], 1) << name;
      } else {
        EXPECT_GT(planner["rank"], 1) << name;
      }
    }
  }
}

TEST(BenchCommand, RankRecomputesTheSameRankingFromTheDatabase) {
  const auto& campaign = thesisCampaign();
  const auto again = freshTempDirectory("bench_rank_again");
  const auto result = runArcplan(
      {"bench", "rank", "--db", (campaign.out / "benchmark.db").string(), "--out", again.string(), "--no-plots"});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(readFile(again / "ranking.csv"), readFile(campaign.out / "ranking.csv"));
  auto first = nlohmann::json::parse(readFile(campaign.out / "ranking.json"));
  auto second = nlohmann::json::parse(readFile(again / "ranking.json"));
  EXPECT_EQ(first["planners"], second["planners"]);
  EXPECT_NE(result.out.find("| rank | planner |"), std::string::npos);
}

TEST(BenchCommand, RankDrawsBoxPlotsSpeedProfilesAndTcpPaths) {
  const auto& campaign = thesisCampaign();
  const auto out = freshTempDirectory("bench_plots");
  // The database with the plot data of one problem only (found next to it), to keep the test short:
  // the other problem gets box plots alone.
  std::filesystem::copy(campaign.out / "benchmark.db", out / "benchmark.db");
  std::filesystem::create_directories(out / "paths" / "thesis");
  std::filesystem::copy(campaign.out / "paths" / "thesis" / "obstacle", out / "paths" / "thesis" / "obstacle",
                        std::filesystem::copy_options::recursive);
  const auto result = runArcplan({"bench", "rank", "--db", (out / "benchmark.db").string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  for (const char* plot : {"boxplots_all.png", "boxplots_thesis_obstacle.png", "boxplots_thesis_straight.png",
                           "speed_thesis_obstacle.png", "paths3d_thesis_obstacle.png"}) {
    const auto file = out / "plots" / plot;
    ASSERT_TRUE(std::filesystem::exists(file)) << plot << "\n" << result.err;
    EXPECT_EQ(readFile(file).substr(1, 3), "PNG") << plot;
  }
  EXPECT_FALSE(std::filesystem::exists(out / "plots" / "speed_thesis_straight.png"));  // no data copied
  EXPECT_TRUE(temporaryFilesBelow(out).empty());
}

TEST(BenchCommand, ResumingSkipsCompletedJobsAndKeepsTheirLogs) {
  const auto& campaign = thesisCampaign();
  std::map<std::filesystem::path, std::string> before;
  for (const auto& log : filesBelow(campaign.out / "logs", ".log")) before[log] = readFile(log);
  const auto result = runArcplan(campaignArguments(campaign.out));
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.err.find("0 job(s) run, 10 already done"), std::string::npos) << result.err;
  for (const auto& [log, text] : before) EXPECT_EQ(readFile(log), text) << log;
}

TEST(BenchCommand, OtherSettingsInAnExistingCampaignDirectoryAreRefused) {
  const auto& campaign = thesisCampaign();
  const auto manifest = readFile(campaign.out / "campaign.json");
  const auto result = runArcplan(campaignArguments(campaign.out, "3"));
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find("other settings (runs"), std::string::npos) << result.err;
  EXPECT_EQ(readFile(campaign.out / "campaign.json"), manifest);
  EXPECT_EQ(filesBelow(campaign.out / "logs", ".log").size(), 10u);
}

TEST(BenchCommand, ShardsRunWithGnuParallelMergeToTheJobsOfOneRun) {
  const auto dir = freshTempDirectory("bench_shards");
  const std::string common =
      "bench --suite thesis --planners arc-h0.50r,arc-auto,RRTConnect --runs 1 --time 0.5 -j 1 "
      "--no-plots --quiet";
  const std::string command = "parallel --will-cite --halt now,fail=1 " + std::string(ARCPLAN_EXECUTABLE) + " " +
                              common + " --shard {}/2 --out " + (dir / "shard{}").string() + " ::: 1 2 > " +
                              (dir / "parallel.out").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << readFile(dir / "parallel.out");
  const auto shard1 = filesBelow(dir / "shard1" / "logs", ".log"), shard2 = filesBelow(dir / "shard2" / "logs", ".log");
  EXPECT_EQ(shard1.size(), 3u);
  EXPECT_EQ(shard2.size(), 3u);
  EXPECT_FALSE(std::filesystem::exists(dir / "shard1" / "benchmark.db"));  // a shard alone is not the campaign

  const auto merged = runArcplan({"bench", "rank", "--logs", (dir / "shard1").string(), (dir / "shard2").string(),
                                  "--db", (dir / "merged" / "benchmark.db").string(), "--no-plots"});
  ASSERT_EQ(merged.exitCode, 0) << merged.err;
  auto single = runArcplan({"bench", "--suite", "thesis", "--planners", "arc-h0.50r,arc-auto,RRTConnect", "--runs", "1",
                            "--time", "0.5", "-j", "1", "--no-plots", "--quiet", "--out", (dir / "single").string()});
  ASSERT_EQ(single.exitCode, 0) << single.err;

  const std::string jobs =
      "SELECT experiments.name, plannerConfigs.name, COUNT(*) FROM runs "
      "JOIN experiments ON runs.experimentid = experiments.id "
      "JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id "
      "GROUP BY experiments.name, plannerConfigs.name ORDER BY 1, 2";
  const auto mergedJobs = query(dir / "merged" / "benchmark.db", jobs);
  EXPECT_EQ(mergedJobs.size(), 6u);
  EXPECT_EQ(mergedJobs, query(dir / "single" / "benchmark.db", jobs));
  // Deterministic planners give the same numbers whichever shard ran them.
  const std::string arc =
      "SELECT experiments.name, plannerConfigs.name, tcp_path_length FROM runs "
      "JOIN experiments ON runs.experimentid = experiments.id "
      "JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id "
      "WHERE plannerConfigs.name LIKE 'geometric_arc%' ORDER BY 1, 2";
  EXPECT_EQ(query(dir / "merged" / "benchmark.db", arc), query(dir / "single" / "benchmark.db", arc));
  EXPECT_TRUE(std::filesystem::exists(dir / "merged" / "ranking.json"));
}

// Starts `arcplan args...` without waiting; stdout/stderr go to files in `dir`.
pid_t startArcplan(const std::vector<std::string>& arguments, const std::filesystem::path& dir) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<std::string> copies = arguments;
    std::string executable = ARCPLAN_EXECUTABLE;
    std::vector<char*> argv{executable.data()};
    for (auto& a : copies) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (!freopen((dir / "stdout").c_str(), "w", stdout) || !freopen((dir / "stderr").c_str(), "w", stderr)) _exit(126);
    execv(executable.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

bool waitForLogs(const std::filesystem::path& logs, std::size_t count, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    if (filesBelow(logs, ".log").size() >= count) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

int exitCodeOf(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// RRTstar always plans for its whole time limit, so each job takes runs x time and the interrupt lands mid-job.
TEST(BenchCommand, CtrlCKeepsCompletedJobLogsWritesNothingHalfDoneAndResumes) {
  const auto dir = freshTempDirectory("bench_interrupt");
  const auto out = dir / "campaign";
  const std::vector<std::string> arguments{"bench",  "--suite",    "thesis", "--planners", "RRTstar",
                                           "--runs", "4",          "--time", "0.25",       "-j",
                                           "1",      "--no-plots", "--out",  out.string()};
  const pid_t pid = startArcplan(arguments, dir);
  ASSERT_TRUE(waitForLogs(out / "logs", 1, 30.0)) << readFile(dir / "stderr");
  kill(pid, SIGINT);
  EXPECT_EQ(exitCodeOf(pid), 130) << readFile(dir / "stderr");
  EXPECT_NE(readFile(dir / "stderr").find("interrupted"), std::string::npos);
  EXPECT_EQ(filesBelow(out / "logs", ".log").size(), 1u);
  EXPECT_TRUE(temporaryFilesBelow(out).empty());
  EXPECT_FALSE(std::filesystem::exists(out / "benchmark.db"));
  EXPECT_FALSE(std::filesystem::exists(out / "ranking.md"));

  const auto resumed = runArcplan(arguments);
  ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("1 job(s) run, 1 already done"), std::string::npos) << resumed.err;
  EXPECT_TRUE(std::filesystem::exists(out / "benchmark.db"));
  EXPECT_EQ(query(out / "benchmark.db", "SELECT COUNT(*) FROM runs")[0][0], "8");
}

TEST(BenchCommand, InterruptingTheParentStopsItsWorkerProcesses) {
  const auto dir = freshTempDirectory("bench_interrupt_workers");
  const auto out = dir / "campaign";
  const pid_t pid = startArcplan({"bench", "--suite", "thesis", "--planners", "RRTstar,PRMstar", "--runs", "6",
                                  "--time", "0.2", "-j", "2", "--no-plots", "--out", out.string()},
                                 dir);
  // Signal the campaign process alone (as a job scheduler may): it tells its workers to stop.
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  kill(pid, SIGINT);
  EXPECT_EQ(exitCodeOf(pid), 130) << readFile(dir / "stderr");
  EXPECT_LT(filesBelow(out / "logs", ".log").size(), 4u);
  EXPECT_TRUE(temporaryFilesBelow(out).empty());
  EXPECT_FALSE(std::filesystem::exists(out / "benchmark.db"));
}

struct BadInput {
  std::vector<std::string> arguments;
  std::string expected;
  int exitCode;  // docs/cli.md: 1 bad input, 2 a wrong command line
};

TEST(BenchCommand, BadInputIsRefusedBeforeAnythingIsWritten) {
  const auto dir = freshTempDirectory("bench_bad");
  const auto out = (dir / "out").string();
  const std::vector<BadInput> cases{
      {{"bench", "--suite", "nowhere", "--out", out}, "built-in: generated, mbm-ur5, thesis", 1},
      {{"bench", "--shard", "3/2", "--out", out}, "--shard: '3/2'", 2},
      {{"bench", "--runs", "0", "--out", out}, "--runs must be at least 1", 2},
      {{"bench", "--time", "0", "--out", out}, "--time must be a positive", 2},
      {{"bench", "--vmax", "-1", "--out", out}, "--vmax must be a positive", 2},
      {{"bench", "--workers", "0", "--out", out}, "--workers must be at least 1", 2},
      {{"bench", "--planners", "RRTConnect,NoSuchPlanner", "--runs", "1", "--out", out}, "NoSuchPlanner", 1},
  };
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.arguments[1] + " " + bad.arguments[2]);
    const auto result = runArcplan(bad.arguments);
    EXPECT_EQ(result.exitCode, bad.exitCode) << result.err;
    EXPECT_NE(result.err.find("arcplan: error: "), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(bad.expected), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  }
}

TEST(BenchCommand, RankRefusesFilesThatAreNotBenchmarkDatabases) {
  const auto dir = freshTempDirectory("bench_rank_bad");
  auto result = runArcplan({"bench", "rank", "--db", (dir / "missing.db").string()});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find("missing.db not found"), std::string::npos) << result.err;

  std::ofstream(dir / "text.db") << "not a database\n";
  result = runArcplan({"bench", "rank", "--db", (dir / "text.db").string(), "--out", (dir / "ranked").string()});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find("not an OMPL benchmark database"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "ranked" / "ranking.md"));

  result = runArcplan({"bench", "rank", "--logs", (dir / "nothing_here").string(), "--db", (dir / "x.db").string()});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find("does not exist"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.db"));
}

}  // namespace
}  // namespace arcplan::testing
