// arcplan bench: benchmark campaigns (OMPL logs, database, ranking, plots) and `bench rank`.
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "arcplan/benchmarks/campaign.h"
#include "arcplan/benchmarks/moveit_problems.h"
#include "arcplan/benchmarks/progress.h"
#include "arcplan/benchmarks/ranking.h"
#include "arcplan/benchmarks/statistics_database.h"
#include "arcplan/benchmarks/suite.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/common/error.h"
#include "cli_support.h"
#include "commands.h"
#include "exit_codes.h"

namespace arcplan::apps {
namespace {

struct BenchOptions {
  std::string suite = "thesis";
  std::vector<std::string> planners;
  std::optional<unsigned> runs;
  std::optional<double> time;
  std::optional<long long> budget;
  std::optional<double> vMax;
  std::string out;
  std::string shard = "1/1";
  unsigned workers = 1;  // addWorkersOption: all cores
  bool noPlots = false;
  bool quiet = false;
  std::string json;
  std::string html;
};

struct RankOptions {
  std::string database;
  std::vector<std::string> logs;
  std::string out;
  bool noPlots = false;
  std::string json;
  std::string html;
};

void printNotes(const std::vector<std::string>& notes) {
  for (const auto& note : notes) std::cerr << "bench: note: " << note << "\n";
}

void printOutputs(const std::filesystem::path& directory, const std::filesystem::path& database) {
  std::cout << "\ndatabase  " << database.string() << "\nranking   " << (directory / "ranking.md").string() << ", "
            << (directory / "ranking.json").string() << ", " << (directory / "ranking.csv").string() << "\n";
  if (std::filesystem::exists(directory / "plots"))
    std::cout << "plots     " << (directory / "plots").string() << "/\n";
}

void runBench(const BenchOptions& options) {
  const DropStdout quiet(options.json == "-");
  auto suite = benchmarks::loadSuite(benchmarks::findSuite(options.suite));
  if (!options.planners.empty()) benchmarks::selectPlanners(suite, options.planners);
  try {
    benchmarks::applyOverrides(suite, {options.runs, options.time, options.budget, options.vMax});
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  requireWorkers(options.workers);

  benchmarks::CampaignOptions campaign;
  campaign.outDirectory =
      options.out.empty() ? std::filesystem::path("results") / suite.name : std::filesystem::path(options.out);
  try {
    campaign.shard = benchmarks::parseShard(options.shard);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  campaign.workers = options.workers;
  campaign.plots = !options.noPlots;
  campaign.showProgress = !options.quiet;

  std::cerr << "bench: suite " << suite.name << " (" << suite.sourceFile.string() << "): " << suite.problems.size()
            << " problems x " << suite.planners.size() << " planners, " << suite.runs << " runs of at most "
            << suite.timeLimit << " s";
  if (suite.iterationBudget) std::cerr << " and " << *suite.iterationBudget << " iterations";
  std::cerr << ", vmax " << suite.vMax << " m/s";
  if (campaign.shard.count > 1) std::cerr << ", shard " << campaign.shard.index << "/" << campaign.shard.count;
  std::cerr << " -> " << campaign.outDirectory.string() << "\n";
  // MoveIt problems: start and goal checked under the exact meshes; invalid ones are reported, not planned.
  const std::string validity = benchmarks::validityTable(suite);
  if (!validity.empty()) {
    std::cerr << "bench: MoveIt problems' start and goal under the exact meshes (" << suite.excludedProblems.size()
              << " problem(s) not planned):\n"
              << validity;
  }

  const auto result = benchmarks::runCampaign(suite, campaign);
  std::cerr << "bench: " << result.jobsRun << " job(s) run, " << result.jobsSkipped << " already done, of "
            << result.jobsInShard << " in this shard; " << benchmarks::formatDuration(result.wallTime) << " with up to "
            << campaign.workers << " worker process(es)\n";
  printNotes(result.notes);

  const auto document = benchmarks::campaignSummaryJson(suite, campaign, result);
  if (!options.json.empty()) writeJson(options.json, document);

  if (result.interrupted) {
    std::cerr << "bench: interrupted — " << result.jobsDoneInCampaign << " of " << result.jobsInCampaign
              << " jobs are complete and their logs are kept in " << (campaign.outDirectory / "logs").string()
              << "; run the same command again to resume\n";
    throw CLI::RuntimeError(toInt(ExitCode::Interrupted));
  }
  if (result.ranking) {
    std::cout << "\n" << benchmarks::rankingTerminalTable(*result.ranking);
    printOutputs(campaign.outDirectory, campaign.outDirectory / "benchmark.db");
    if (!options.html.empty()) writeHtmlReport(campaign.outDirectory, options.html);
  } else if (!options.html.empty()) {
    std::cerr << "bench: note: --html: the report is written once every job of the campaign is done\n";
  }
}

void runRank(const RankOptions& options) {
  const DropStdout quiet(options.json == "-");
  const std::filesystem::path database = options.database;
  if (!options.logs.empty()) {
    std::vector<std::filesystem::path> roots(options.logs.begin(), options.logs.end());
    const auto logs = benchmarks::findLogs(roots);
    if (logs.empty()) throw Error("--logs: no *.log files under the given paths");
    std::cerr << "bench rank: building " << database.string() << " from " << logs.size()
              << " OMPL logs with ompl_benchmark_statistics\n";
    benchmarks::buildBenchmarkDatabase(logs, database);
  }
  benchmarks::ReportOptions report;
  report.outDirectory = options.out.empty() ? database.parent_path() : std::filesystem::path(options.out);
  if (report.outDirectory.empty()) report.outDirectory = ".";
  report.plots = !options.noPlots;
  // Median-run data of campaigns: next to the database and next to each merged log folder.
  report.pathDirectories.push_back(report.outDirectory / "paths");
  if (!database.parent_path().empty()) report.pathDirectories.push_back(database.parent_path() / "paths");
  for (const auto& logs : options.logs) {  // a shard's output folder, or its logs/ folder
    report.pathDirectories.push_back(std::filesystem::path(logs) / "paths");
    report.pathDirectories.push_back(std::filesystem::path(logs).parent_path() / "paths");
  }
  std::vector<std::string> notes;
  const auto ranking = benchmarks::reportFromDatabase(database, report, notes);
  printNotes(notes);
  if (!options.json.empty()) writeJson(options.json, benchmarks::rankingJson(ranking));
  std::cout << benchmarks::rankingTerminalTable(ranking);
  printOutputs(report.outDirectory, database);
  if (!options.html.empty()) writeHtmlReport(database, options.html);
}

}  // namespace

void registerBenchCommand(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* command =
      app.add_subcommand("bench", "benchmark planners on a problem suite: OMPL logs, database, ranking, plots");
  command->footer(
      "Runs the arc planner against OMPL's planners on a problem suite: OMPL benchmark logs, an SQLite database "
      "made by ompl_benchmark_statistics, a ranking (ranking.md/json/csv) by success rate and execution time after "
      "PCHIP scaling at the TCP speed limit, and plots. Resumable (completed jobs are skipped) and shardable.");
  command->add_option("--suite", options->suite, "built-in suite name (thesis, generated) or a suite YAML file")
      ->capture_default_str();
  command
      ->add_option("--planners", options->planners,
                   "only these planner configurations of the suite, comma-separated (a name the suite does not "
                   "configure is taken as a registry planner with default parameters)")
      ->delimiter(',');
  command->add_option("--runs", options->runs, "runs per planner and problem (default: the suite's)");
  command->add_option("--time", options->time, "time limit per run [s] (default: the suite's)");
  command->add_option("--budget", options->budget,
                      "iterations per run (default: the suite's `budget`, else none): runs end after this many "
                      "whatever the machine's load, so they repeat exactly; --time becomes a safety cap "
                      "(docs/reproducibility.md)");
  command->add_option("--vmax", options->vMax,
                      "TCP speed limit of the time scaling [m/s] (default: the suite's, 0.25)");
  command->add_option("--out", options->out, "output directory (default: results/<suite>)");
  command
      ->add_option("--shard", options->shard,
                   "run shard K of N (K = 1..N): a deterministic 1/N share of the (problem, planner) jobs, e.g. "
                   "--shard $SLURM_ARRAY_TASK_ID/N")
      ->capture_default_str();
  addWorkersOption(*command, options->workers);
  addCollisionModeOption(*command);
  command->add_flag("--no-plots", options->noPlots, "do not draw the PNG plots");
  command->add_flag("--quiet", options->quiet, "no progress output");
  command->add_option("--json", options->json, "write the campaign summary and ranking as JSON ('-' for stdout)");
  command->add_option("--html", options->html,
                      "also write the campaign's self-contained HTML report to this file (docs/report.md)");

  auto rankOptions = std::make_shared<RankOptions>();
  CLI::App* rank = command->add_subcommand(
      "rank",
      "Recompute the ranking (and plots) from a benchmark database, e.g. one merged from the logs of several "
      "shards; with --logs, first build the database from those logs with ompl_benchmark_statistics");
  rank->add_option("--db", rankOptions->database, "benchmark database (SQLite, made by ompl_benchmark_statistics)")
      ->required();
  rank->add_option("--logs", rankOptions->logs,
                   "OMPL log files or folders (searched recursively for *.log) to (re)build --db from first, e.g. "
                   "the output folders of all shards");
  rank->add_option("--out", rankOptions->out, "folder for ranking.{md,json,csv} and plots/ (default: the database's)");
  rank->add_flag("--no-plots", rankOptions->noPlots, "do not draw the PNG plots");
  rank->add_option("--json", rankOptions->json, "write the ranking as JSON ('-' for stdout)");
  rank->add_option("--html", rankOptions->html,
                   "also write the self-contained HTML report of the database to this file");
  rank->callback([rankOptions] { runRank(*rankOptions); });

  registerBenchCompareCommands(*command);

  command->require_subcommand(0, 1);
  command->callback([options, command] {
    if (!command->get_subcommands().empty()) return;  // rank, compare or baseline ran instead
    runBench(*options);
  });
}

}  // namespace arcplan::apps
