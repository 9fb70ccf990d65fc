#pragma once
// Where a campaign keeps what in its output directory (the layout is in campaign.h), and the files
// that describe the campaign itself: campaign.json (its settings) and the plot scenes. Internal to
// arcplan::benchmarks.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <sys/types.h>

#include "arcplan/benchmarks/campaign.h"
#include "job_runner.h"

namespace arcplan::benchmarks::detail {

// Throws arcplan::Error naming the directory when it cannot be created.
void createDirectory(const std::filesystem::path& directory);

// Writes campaign.json, or checks that the existing one has the suite's settings: a resumed or
// sharded campaign must run exactly the settings its directory was started with, since one ranking
// of runs with different settings would compare incomparable runs. Throws arcplan::Error otherwise.
void claimOutputDirectory(const std::filesystem::path& directory, const Suite& suite);

// A running campaign's claim on its output directory: the file campaign-K-of-N.lock (JSON: pid, host,
// shard, start time) for its shard. Campaigns whose shards share no job (2/8 and 5/8) may run in
// one directory at once; any other pair may not, since both would run the same jobs. Lock files are
// checked and written under flock(2) of the directory, so two campaigns starting together cannot both
// take it.
class OutputDirectoryLock {
public:
  // Throws arcplan::Error naming the holder (pid, host, shard, start, lock file) when a running campaign
  // shares jobs with `shard`. A lock of a process that is gone from this host is taken over, with a
  // note; a lock from another host is never taken over (its process cannot be checked from here).
  OutputDirectoryLock(const std::filesystem::path& directory, const Shard& shard, std::size_t jobCount,
                      std::vector<std::string>& notes);
  OutputDirectoryLock(const OutputDirectoryLock&) = delete;
  OutputDirectoryLock& operator=(const OutputDirectoryLock&) = delete;
  ~OutputDirectoryLock();  // removes the lock file (in the process that took it, not in forked workers)

  // Hosts other than this one with a campaign running in the directory now.
  const std::vector<std::string>& otherHosts() const { return otherHosts_; }

private:
  std::filesystem::path file_;
  pid_t owner_;
  std::vector<std::string> otherHosts_;
};

// Removes the temporary files (<name>.tmp.<pid>...) below `directory` whose writing process is gone
// from this host: what a killed campaign or worker leaves. Temporaries of live processes (another
// shard writing now) stay. Returns the removed files. Call it holding the directory's lock, and not
// while a campaign on another host writes there (its pids mean nothing here).
std::vector<std::filesystem::path> removeAbandonedTemporaries(const std::filesystem::path& directory);

// Why the job's existing log does not count as done (benchmarkLogProblem with the job's experiment,
// planner and run count), or nullopt when it is complete.
std::optional<std::string> jobLogProblem(const std::filesystem::path& out, const Suite& suite, const Job& job);

std::string jobLabel(const Suite& suite, const Job& job);  // "<problem> · <planner>"
JobFiles jobFiles(const std::filesystem::path& out, const Suite& suite, const Job& job);

// Problems listed under the suite's `plots` get median-run files and a scene.json for the plots.
bool isPlotProblem(const Suite& suite, const Problem& problem);
std::filesystem::path pathsDirectory(const std::filesystem::path& out, const Suite& suite, const Problem& problem);
// What the 3D plot needs besides the paths: obstacles and the TCP positions of start and goal.
void writePlotScene(const std::filesystem::path& file, const Problem& problem, double vMax);

}  // namespace arcplan::benchmarks::detail
