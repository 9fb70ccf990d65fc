#pragma once
// A running campaign's lock on its output directory, and the cleanup of temporaries that killed
// campaigns leave there. Internal to arcplan::benchmarks.
#include <filesystem>
#include <string>
#include <vector>

#include <sys/types.h>

#include "arcplan/benchmarks/campaign.h"

namespace arcplan::benchmarks::detail {

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

}  // namespace arcplan::benchmarks::detail
