#include "arcplan/benchmarks/campaign.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <iostream>

#include <signal.h>
#include <unistd.h>

#include "arcplan/benchmarks/generated_problems.h"
#include "arcplan/benchmarks/interrupt.h"
#include "arcplan/benchmarks/progress.h"
#include "arcplan/benchmarks/statistics_database.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "campaign_layout.h"
#include "campaign_lock.h"
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
      if (problem.kind != "scene file" && !std::filesystem::exists(file)) collision::writeScene(problem.scene, file);
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
  ProgressDisplay shown(options.showProgress ? std::cerr : discard,
                        options.showProgress && ::isatty(STDERR_FILENO) != 0, labels, suite.runs);
  const auto runJob = [&](std::size_t i, const std::function<void(unsigned, bool)>& onRunFinished) {
    const Job& job = pending[i];
    return detail::runJob(suite, suite.problems[job.problem], suite.planners[job.planner],
                          detail::jobFiles(options.outDirectory, suite, job), onRunFinished);
  };
  detail::PoolResult result;
  {
    const InterruptHandlers handlers;
    const unsigned workers = std::max(1u, std::min<unsigned>(options.workers, static_cast<unsigned>(pending.size())));
    result = detail::runJobs(
        pending.size(), workers, runJob, [&](std::size_t i) { return labels[i]; }, shown);
    shown.finish();
    if (interruptRequested()) result.interrupted = true;
  }
  clearInterruptRequest();
  return result;
}

// Notes about the state the output directory was found in go to stderr at once: they explain what the
// campaign does next (and a campaign that fails later still shows them).
void printNote(const std::string& note) { std::cerr << "bench: note: " << note << "\n"; }

// A write past RLIMIT_FSIZE raises SIGXFSZ, whose default action kills the process without a word;
// ignored, the write fails with EFBIG like a write to a full disk, and the campaign reports it.
class FileSizeSignalIgnored {
public:
  FileSizeSignalIgnored() { ::sigaction(SIGXFSZ, &ignore(), &previous_); }
  ~FileSizeSignalIgnored() { ::sigaction(SIGXFSZ, &previous_, nullptr); }
  FileSizeSignalIgnored(const FileSizeSignalIgnored&) = delete;
  FileSizeSignalIgnored& operator=(const FileSizeSignalIgnored&) = delete;

private:
  static const struct sigaction& ignore() {
    static const struct sigaction action = [] {
      struct sigaction a {};
      a.sa_handler = SIG_IGN;
      sigemptyset(&a.sa_mask);
      return a;
    }();
    return action;
  }
  struct sigaction previous_ {};
};

// The shard's jobs without a complete log. An existing log that is not complete (cut short by a crash
// or a full disk, garbled) is reported and its job runs again; the new log replaces it.
std::vector<Job> pendingJobs(const Suite& suite, const std::vector<Job>& share, const std::filesystem::path& out) {
  std::vector<Job> pending;
  for (const auto& job : share) {
    const auto log = jobLogPath(out, suite, job);
    if (!std::filesystem::exists(log)) {
      pending.push_back(job);
    } else if (const auto problem = detail::jobLogProblem(out, suite, job)) {
      printNote(log.string() + " is incomplete (" + *problem + "): its job runs again");
      pending.push_back(job);
    }
  }
  return pending;
}

}  // namespace

CampaignResult runCampaign(const Suite& suite, const CampaignOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.outDirectory.empty()) throw Error("--out: an output directory is required");
  detail::checkPlannerConfigurations(suite);  // bad planners or parameters: nothing is written
  detail::createDirectory(options.outDirectory);
  const auto all = campaignJobs(suite);
  std::vector<std::string> lockNotes;
  const detail::OutputDirectoryLock lock(options.outDirectory, options.shard, all.size(), lockNotes);
  for (const auto& note : lockNotes) printNote(note);
  detail::claimOutputDirectory(options.outDirectory, suite);
  if (lock.otherHosts().empty()) {
    const auto removed = detail::removeAbandonedTemporaries(options.outDirectory);
    if (!removed.empty()) {
      printNote("removed " + std::to_string(removed.size()) +
                " temporary file(s) of a campaign that was killed, e.g. " + removed.front().string());
    }
  }
  const FileSizeSignalIgnored fileSizeSignal;

  CampaignResult result;
  const auto share = shardJobs(all, options.shard);
  const auto done = [&](const Job& job) {
    return std::filesystem::exists(jobLogPath(options.outDirectory, suite, job)) &&
           !detail::jobLogProblem(options.outDirectory, suite, job);
  };
  const std::vector<Job> pending = pendingJobs(suite, share, options.outDirectory);
  result.jobsInShard = share.size();
  result.jobsSkipped = share.size() - pending.size();
  result.jobsInCampaign = all.size();

  writeProblemFiles(suite, options.outDirectory);
  const auto outcome = runPendingJobs(suite, pending, options);
  result.jobsRun = outcome.completed;
  result.interrupted = outcome.interrupted;
  result.notes = outcome.failures;
  result.jobsDoneInCampaign = static_cast<std::size_t>(std::count_if(all.begin(), all.end(), done));

  if (!outcome.outputFailure.empty()) {
    throw Error("the campaign stopped: " + outcome.outputFailure + "\n" + std::to_string(result.jobsDoneInCampaign) +
                " of " + std::to_string(result.jobsInCampaign) + " jobs are complete and their logs are kept in " +
                (options.outDirectory / "logs").string() +
                "; make room (or raise the file size limit) and run the same command again to resume");
  }
  if (!outcome.failures.empty()) {
    std::string message = std::to_string(outcome.failures.size()) + " job(s) failed:";
    for (const auto& failure : outcome.failures) message += "\n  " + failure;
    throw Error(message);
  }
  if (!result.interrupted && result.jobsDoneInCampaign == result.jobsInCampaign) {
    const auto database = options.outDirectory / "benchmark.db";
    try {
      buildBenchmarkDatabase(findLogs({options.outDirectory / "logs" / suite.name}), database);
    } catch (const Error& e) {
      throw Error(std::string(e.what()) + "\nevery job's log is complete and kept in " +
                  (options.outDirectory / "logs").string() + "; run the same command again to build " +
                  database.string());
    }
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

nlohmann::json campaignSummaryJson(const Suite& suite, const CampaignOptions& options, const CampaignResult& result) {
  nlohmann::json document{{"suite", suite.name},
                          {"out", options.outDirectory.string()},
                          {"shard", std::to_string(options.shard.index) + "/" + std::to_string(options.shard.count)},
                          {"jobs_in_shard", result.jobsInShard},
                          {"jobs_run", result.jobsRun},
                          {"jobs_skipped", result.jobsSkipped},
                          {"jobs_in_campaign", result.jobsInCampaign},
                          {"jobs_done_in_campaign", result.jobsDoneInCampaign},
                          {"interrupted", result.interrupted},
                          {"wall_time_s", result.wallTime}};
  if (result.ranking) document["ranking"] = rankingJson(*result.ranking);
  return document;
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
