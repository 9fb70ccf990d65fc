#include "arcplan/benchmarks/campaign.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <iostream>
#include <iterator>

#include <unistd.h>

#include "arcplan/benchmarks/generated_problems.h"
#include "arcplan/benchmarks/interrupt.h"
#include "arcplan/benchmarks/progress.h"
#include "arcplan/benchmarks/statistics_database.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "campaign_layout.h"
#include "campaign_plots.h"
#include "job_runner.h"
#include "worker_pool.h"

namespace arcplan::benchmarks {

namespace {

// Generated problems as scene files (`arcplan plan --scene` reproduces one) and the plot scenes.
void writeProblemFiles(const Suite& suite, const std::filesystem::path& out) {
  for (const auto& problem : suite.problems) {
    if (suite.generator) {
      const auto file = out / "scenes" / (problem.name + ".yaml");
      if (problem.kind != "scene file" && !std::filesystem::exists(file)) writeFileAtomically(file, sceneToYaml(problem.scene));
    }
    if (detail::isPlotProblem(suite, problem)) {
      const auto file = detail::pathsDirectory(out, suite, problem) / "scene.json";
      if (!std::filesystem::exists(file)) detail::writePlotScene(file, problem, suite.vMax);
    }
  }
}

// Runs `pending` with progress on stderr; Ctrl-C stops between runs (handlers restored afterwards).
detail::PoolResult runPendingJobs(const Suite& suite, const std::vector<Job>& pending, const CampaignOptions& options) {
  std::vector<std::string> labels;
  for (const auto& job : pending) labels.push_back(detail::jobLabel(suite, job));
  std::ostream discard(nullptr);  // no buffer: swallows everything
  ProgressDisplay shown(options.showProgress ? std::cerr : discard, options.showProgress && ::isatty(STDERR_FILENO) != 0,
                        labels, suite.runs);
  const auto runJob = [&](std::size_t i, const std::function<void(unsigned, bool)>& onRunFinished) {
    const Job& job = pending[i];
    return detail::runJob(suite, suite.problems[job.problem], suite.planners[job.planner],
                          detail::jobFiles(options.outDirectory, suite, job), onRunFinished);
  };
  detail::PoolResult result;
  {
    const InterruptHandlers handlers;
    const unsigned workers = std::max(1u, std::min<unsigned>(options.workers, static_cast<unsigned>(pending.size())));
    result = detail::runJobs(pending.size(), workers, runJob, [&](std::size_t i) { return labels[i]; }, shown);
    shown.finish();
    if (interruptRequested()) result.interrupted = true;
  }
  clearInterruptRequest();
  return result;
}

}  // namespace

CampaignResult runCampaign(const Suite& suite, const CampaignOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.outDirectory.empty()) throw Error("--out: an output directory is required");
  detail::checkPlannerConfigurations(suite);  // bad planners or parameters: nothing is written
  detail::createDirectory(options.outDirectory);
  detail::claimOutputDirectory(options.outDirectory, suite);

  CampaignResult result;
  const auto all = campaignJobs(suite);
  const auto share = shardJobs(all, options.shard);
  const auto done = [&](const Job& job) { return std::filesystem::exists(jobLogPath(options.outDirectory, suite, job)); };
  std::vector<Job> pending;
  std::copy_if(share.begin(), share.end(), std::back_inserter(pending), [&](const Job& job) { return !done(job); });
  result.jobsInShard = share.size();
  result.jobsSkipped = share.size() - pending.size();
  result.jobsInCampaign = all.size();

  writeProblemFiles(suite, options.outDirectory);
  const auto outcome = runPendingJobs(suite, pending, options);
  result.jobsRun = outcome.completed;
  result.interrupted = outcome.interrupted;
  result.notes = outcome.failures;
  result.jobsDoneInCampaign = static_cast<std::size_t>(std::count_if(all.begin(), all.end(), done));

  if (!outcome.failures.empty()) {
    std::string message = std::to_string(outcome.failures.size()) + " job(s) failed:";
    for (const auto& failure : outcome.failures) message += "\n  " + failure;
    throw Error(message);
  }
  if (!result.interrupted && result.jobsDoneInCampaign == result.jobsInCampaign) {
    const auto database = options.outDirectory / "benchmark.db";
    buildBenchmarkDatabase(findLogs({options.outDirectory / "logs" / suite.name}), database);
    ReportOptions report;
    report.outDirectory = options.outDirectory;
    report.pathDirectories = {options.outDirectory / "paths"};
    report.plots = options.plots;
    result.ranking = reportFromDatabase(database, report, result.notes);
  } else if (!result.interrupted) {
    result.notes.push_back(std::to_string(result.jobsDoneInCampaign) + " of " + std::to_string(result.jobsInCampaign) +
                           " jobs of the campaign are done in " + options.outDirectory.string() +
                           "; the database and ranking are made when the last shard finishes in this directory, or "
                           "merge the shards' logs with `arcplan bench rank --logs DIR... --db F`");
  }
  result.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

Ranking reportFromDatabase(const std::filesystem::path& database, const ReportOptions& options,
                           std::vector<std::string>& notes) {
  auto ranking = rankDatabase(database);
  detail::createDirectory(options.outDirectory);
  writeRanking(ranking, options.outDirectory);
  if (options.plots) detail::makePlots(database, ranking, options, notes);
  return ranking;
}

}  // namespace arcplan::benchmarks
