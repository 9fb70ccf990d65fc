#pragma once
// A benchmark campaign: every (problem, planner) job of a suite, each run through ompl::tools::Benchmark
// and saved as its own OMPL log, so campaigns shard over machines (--shard K/N), resume after Ctrl-C
// or a crash (a job whose log is complete is done), and merge with ompl_benchmark_statistics.
// docs/reproducibility.md: what survives a crash, a full disk or a second campaign, what repeats.
//
// Output directory layout:
//   campaign.json                 suite settings; a resumed or sharded run must match them
//   campaign-K-of-N.lock          held by the running campaign of shard K/N (pid, host)
//   logs/<problem>/<planner>.log  one OMPL benchmark log per job (experiment "<suite>/<problem>")
//   scenes/<problem>.yaml         generated problems as scene files (arcplan plan --scene ... works)
//   paths/<problem>/...           median run per planner (TCP speed profile, TCP path) for plots
//   benchmark.db                  ompl_benchmark_statistics of all logs, once every job is done
//   ranking.{md,json,csv}, plots/ from benchmark.db
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arcplan/benchmarks/ranking.h"
#include "arcplan/benchmarks/suite.h"

namespace arcplan::benchmarks {

// Shard `index` of `count` (1-based, as Slurm array task ids 1..N).
struct Shard {
  int index = 1;
  int count = 1;
};
// "K/N" with 1 <= K <= N; throws arcplan::Error naming --shard otherwise.
Shard parseShard(const std::string& text);

struct Job {
  std::size_t problem = 0;  // index into Suite::problems
  std::size_t planner = 0;  // index into Suite::planners
  bool operator==(const Job& other) const { return problem == other.problem && planner == other.planner; }
};

// Every (problem, planner) pair, problems outer, in suite order.
std::vector<Job> campaignJobs(const Suite& suite);
// Job i of `jobs` belongs to shard (i mod N) + 1: a deterministic share of N, sizes differing by at most one.
std::vector<Job> shardJobs(const std::vector<Job>& jobs, const Shard& shard);

std::string experimentName(const Suite& suite, const Problem& problem);  // "<suite>/<problem>"
std::filesystem::path jobLogPath(const std::filesystem::path& outDirectory, const Suite& suite, const Job& job);

struct CampaignOptions {
  std::filesystem::path outDirectory;
  Shard shard;
  unsigned workers = 1;  // processes running jobs in parallel (each job stays in one process)
  bool plots = true;
  bool showProgress = true;  // on stderr
};

struct CampaignResult {
  std::size_t jobsInShard = 0;
  std::size_t jobsSkipped = 0;  // already done (resume)
  std::size_t jobsRun = 0;      // completed now
  std::size_t jobsInCampaign = 0;
  std::size_t jobsDoneInCampaign = 0;  // logs present for all shards together
  bool interrupted = false;
  double wallTime = 0.0;           // s
  std::optional<Ranking> ranking;  // when every job of the campaign is done
  std::vector<std::string> notes;  // for the user: plots skipped, how to merge shards, ...
};

// Runs the shard's pending jobs and, once the whole campaign is done, builds benchmark.db, the
// ranking and the plots. Notes on what it found in the output directory (a stale lock taken over,
// temporaries of killed processes removed, incomplete logs run again) go to stderr at once. Throws
// arcplan::Error for bad settings (before any job runs), when the output directory holds a campaign
// with other settings or is locked by a campaign sharing jobs with this shard, or when an output file
// cannot be written (the campaign stops, completed logs stay).
CampaignResult runCampaign(const Suite& suite, const CampaignOptions& options);

// The summary `bench --json` writes (docs/cli.md): suite, out, shard, jobs_in_shard, jobs_run, jobs_skipped,
// jobs_in_campaign, jobs_done_in_campaign, interrupted, wall_time_s, and the ranking once the campaign is done.
nlohmann::json campaignSummaryJson(const Suite& suite, const CampaignOptions& options, const CampaignResult& result);

struct ReportOptions {
  std::filesystem::path outDirectory;                  // ranking files and plots/
  std::vector<std::filesystem::path> pathDirectories;  // campaign "paths" folders for profile and 3D plots
  bool plots = true;
};
// Ranking files (and plots) from a benchmark database; returns the ranking and notes for the user.
Ranking reportFromDatabase(const std::filesystem::path& database, const ReportOptions& options,
                           std::vector<std::string>& notes);

}  // namespace arcplan::benchmarks
