// arcplan bench compare / bench baseline save|check: did planner results get worse between two
// campaigns, or since a committed baseline? Exit code 1 when any row is worse (for CI).
#include <iostream>
#include <memory>
#include <optional>
#include <random>
#include <string>

#include "arcplan/benchmarks/baseline.h"
#include "arcplan/benchmarks/campaign.h"
#include "arcplan/benchmarks/campaign_comparison.h"
#include "arcplan/benchmarks/progress.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/report/comparison_report.h"
#include "cli_support.h"
#include "commands.h"
#include "exit_codes.h"

namespace arcplan::apps {
namespace {

struct ComparisonFlags {
  benchmarks::ComparisonOptions options;
  std::string out;
  std::string json;
  std::string html;
  bool all = false;
};

struct CompareOptions {
  std::string base;
  std::string current;
  ComparisonFlags flags;
};

struct BaselineSaveOptions {
  std::string campaign;
  std::string file;
};

struct BaselineCheckOptions {
  std::string file;
  std::string suite;
  std::string campaignOut;
  unsigned workers = 1;  // addWorkersOption: all cores
  bool quiet = false;
  ComparisonFlags flags;
};

void addComparisonOptions(CLI::App& command, ComparisonFlags& flags) {
  command
      .add_option("--alpha", flags.options.alpha,
                  "family-wise error rate of the stochastic tests after Holm's correction, in (0, 1)")
      ->capture_default_str();
  command
      .add_option("--min-effect", flags.options.minEffect,
                  "smallest change flagged for stochastic planners: relative median change, or success-rate "
                  "difference (0.05 = 5 %, 5 percentage points)")
      ->capture_default_str();
  command
      .add_option("--tolerance", flags.options.tolerance,
                  "exact comparison of zero-variance results, in the metric's unit (m, s, ...)")
      ->capture_default_str();
  command
      .add_option("--solve-time-floor", flags.options.solveTimeFloor,
                  "solve-time changes of the median below this many seconds are never flagged (wall-clock noise)")
      ->capture_default_str();
  command
      .add_option("--metrics", flags.options.metrics,
                  "metric keys to compare besides the success rate, comma-separated (docs/metrics.md)")
      ->delimiter(',')
      ->default_str(joinText(benchmarks::defaultComparedMetrics(), ","));
  command.add_option("--out", flags.out, "write comparison.md, comparison.json and comparison.csv to this folder");
  command.add_option("--json", flags.json, "write the comparison as JSON to this file ('-' for stdout)");
  command.add_option(
      "--html", flags.html,
      "also write the comparison as one self-contained HTML page (verdicts, table, side-by-side box plots)");
  command.add_flag("--all", flags.all, "print every row, also those with verdict \"same\"");
}

// Prints and writes the comparison; exit code 1 when a row is worse.
void reportComparison(const benchmarks::CampaignComparison& comparison, const benchmarks::CampaignResults& base,
                      const benchmarks::CampaignResults& current, const ComparisonFlags& flags) {
  if (!flags.out.empty()) benchmarks::writeComparison(comparison, flags.out);
  if (!flags.json.empty()) writeJson(flags.json, benchmarks::comparisonJson(comparison));
  if (!flags.html.empty()) {
    report::writeComparisonReport(flags.html, comparison, base, current);
    std::cerr << "bench: comparison page " << flags.html << " (open it in a web browser)\n";
  }
  if (flags.json != "-") std::cout << benchmarks::comparisonMarkdown(comparison, !flags.all);
  if (!flags.out.empty()) {
    std::cerr << "bench: comparison written to "
              << (std::filesystem::path(flags.out) / "comparison.{md,json,csv}").string() << "\n";
  }
  const int worse = comparison.count(benchmarks::Verdict::Worse);
  if (worse > 0) {
    std::cerr << "bench: " << worse << " result(s) worse than the base\n";
    throw CLI::RuntimeError(toInt(ExitCode::BadInput));
  }
}

// Options out of range are a wrong command line, not bad input.
void checkOptions(const benchmarks::ComparisonOptions& options) {
  try {
    benchmarks::checkComparisonOptions(options);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

void runCompare(const CompareOptions& options) {
  checkOptions(options.flags.options);
  const auto base = benchmarks::loadCampaignResults(options.base);
  const auto current = benchmarks::loadCampaignResults(options.current);
  reportComparison(benchmarks::compareCampaigns(base, current, options.flags.options), base, current, options.flags);
}

void runBaselineSave(const BaselineSaveOptions& options) {
  const auto baseline = benchmarks::makeBaseline(options.campaign);
  writeFileAtomically(options.file, baseline.dump(1) + "\n");
  std::cerr << "bench baseline: " << baseline.at("results").size() << " (problem, planner) results of "
            << options.campaign << " saved to " << options.file << "\n";
}

// A fresh folder for the re-run campaign (a folder with an earlier campaign would be resumed),
// removed when the check ends unless kept.
class TemporaryCampaignDirectory {
public:
  TemporaryCampaignDirectory() {
    std::random_device device;
    for (int attempt = 0; attempt < 100 && path_.empty(); ++attempt) {
      const auto candidate =
          std::filesystem::temp_directory_path() / ("arcplan-baseline-check-" + std::to_string(device()));
      if (std::filesystem::create_directory(candidate)) path_ = candidate;
    }
    if (path_.empty())
      throw Error("cannot create a temporary folder under " + std::filesystem::temp_directory_path().string());
  }
  TemporaryCampaignDirectory(const TemporaryCampaignDirectory&) = delete;
  TemporaryCampaignDirectory& operator=(const TemporaryCampaignDirectory&) = delete;
  ~TemporaryCampaignDirectory() {
    std::error_code ignored;  // best effort: a leftover folder in the temp directory harms nothing
    if (!kept_) std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }
  void keep() { kept_ = true; }

private:
  std::filesystem::path path_;
  bool kept_ = false;
};

void runBaselineCheck(const BaselineCheckOptions& options) {
  requireWorkers(options.workers);
  checkOptions(options.flags.options);  // before the campaign runs
  const auto baseline = benchmarks::readBaseline(options.file);
  const std::optional<std::filesystem::path> suiteFile =
      options.suite.empty() ? std::nullopt : std::optional<std::filesystem::path>(options.suite);
  const auto suite = benchmarks::suiteForBaseline(baseline, suiteFile);

  benchmarks::CampaignOptions campaign;
  const bool temporary = options.campaignOut.empty();
  std::optional<TemporaryCampaignDirectory> temporaryDirectory;
  if (temporary) temporaryDirectory.emplace();
  campaign.outDirectory = temporary ? temporaryDirectory->path() : std::filesystem::path(options.campaignOut);
  campaign.workers = options.workers;
  campaign.plots = false;
  campaign.showProgress = !options.quiet;
  std::cerr << "bench baseline: running suite " << suite.name << " again (" << suite.problems.size() << " problems x "
            << suite.planners.size() << " planners, " << suite.runs << " runs) -> " << campaign.outDirectory.string()
            << "\n";
  const auto result = benchmarks::runCampaign(suite, campaign);
  if (result.interrupted) {
    if (temporaryDirectory) temporaryDirectory->keep();
    std::cerr << "bench baseline: interrupted; the partial campaign is kept in " << campaign.outDirectory.string()
              << " (resume: the same command with --campaign-out " << campaign.outDirectory.string() << ")\n";
    throw CLI::RuntimeError(toInt(ExitCode::Interrupted));
  }
  std::cerr << "bench baseline: campaign done in " << benchmarks::formatDuration(result.wallTime) << "\n";
  auto current = benchmarks::loadCampaignResults(campaign.outDirectory);
  if (temporary) current.source = "re-run of " + options.file;
  const auto base = benchmarks::baselineResults(baseline, options.file);
  const auto comparison = benchmarks::compareCampaigns(base, current, options.flags.options);
  reportComparison(comparison, base, current, options.flags);
}

}  // namespace

void registerBenchCompareCommands(CLI::App& bench) {
  auto compareOptions = std::make_shared<CompareOptions>();
  CLI::App* compare = bench.add_subcommand(
      "compare",
      "Compare two campaigns planner by planner: better / same / worse per metric; exit code 1 if any is worse");
  compare->footer(
      "BASE and NEW are campaign folders, benchmark databases or baseline files. Runs are matched by problem and "
      "planner configuration name. Zero-variance results (the arc planner) are compared exactly; stochastic ones with "
      "Fisher's exact test (success) and the Mann-Whitney U test (metrics), Holm-corrected. Exit codes: 0 nothing "
      "worse, 1 something worse or bad input, 2 usage error. See docs/benchmarks.md, \"Comparing campaigns\".");
  compare->add_option("BASE", compareOptions->base, "the reference: campaign folder, benchmark.db or baseline file")
      ->required();
  compare
      ->add_option("NEW", compareOptions->current,
                   "the campaign to judge: campaign folder, benchmark.db or baseline file")
      ->required();
  addComparisonOptions(*compare, compareOptions->flags);
  compare->callback([compareOptions] { runCompare(*compareOptions); });

  CLI::App* baseline =
      bench.add_subcommand("baseline", "Save a campaign as a compact baseline file, or check against one (CI)");
  baseline->require_subcommand(1);
  baseline->footer(
      "A baseline is one JSON file holding a campaign's settings and, per problem and planner, the exact values of "
      "deterministic results and 21 quantiles of stochastic ones. Commit it; in CI `check` runs the campaign again "
      "and compares (exit 1 if anything is worse). See docs/benchmarks.md, \"Comparing campaigns\".");

  auto saveOptions = std::make_shared<BaselineSaveOptions>();
  CLI::App* save =
      baseline->add_subcommand("save", "Write the baseline of a finished campaign folder (JSON, to commit)");
  save->add_option("DIR", saveOptions->campaign, "finished campaign folder (campaign.json, benchmark.db)")->required();
  save->add_option("FILE", saveOptions->file, "baseline file to write")->required();
  save->footer(
      "The folder must hold a finished campaign (campaign.json and benchmark.db). The file is written atomically.");
  save->callback([saveOptions] { runBaselineSave(*saveOptions); });

  auto checkOptions = std::make_shared<BaselineCheckOptions>();
  CLI::App* check = baseline->add_subcommand(
      "check", "Run the campaign a baseline describes again and compare it with the baseline; exit code 1 if worse");
  check->add_option("FILE", checkOptions->file, "baseline file (from bench baseline save)")->required();
  check->add_option("--suite", checkOptions->suite,
                    "suite file to run (default: the baseline's suite by name, as `bench --suite NAME` finds it)");
  check->add_option("--campaign-out", checkOptions->campaignOut,
                    "keep the new campaign in this folder (default: a temporary folder, removed afterwards)");
  addWorkersOption(*check, checkOptions->workers);
  check->add_flag("--quiet", checkOptions->quiet, "no progress output");
  check->footer(
      "Runs the baseline's suite, planners and problems with its runs, time limit, v_max and iteration budget, then "
      "compares the baseline (BASE) with the new runs (NEW) as `bench compare` does. Exit codes: 0 nothing worse, 1 "
      "something worse or bad input, 2 usage error, 130 interrupted.");
  addComparisonOptions(*check, checkOptions->flags);
  check->callback([checkOptions] { runBaselineCheck(*checkOptions); });
}

}  // namespace arcplan::apps
