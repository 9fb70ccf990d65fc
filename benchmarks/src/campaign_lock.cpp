// A campaign's claim on its output directory, and what killed campaigns leave behind (campaign_lock.h).
#include "campaign_lock.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fstream>
#include <regex>
#include <sstream>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"

namespace arcplan::benchmarks::detail {
namespace {

std::string hostName() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

struct ProcessStat {
  bool finished = false;     // a zombie: it has ended, its parent has not collected it yet
  long long startTicks = 0;  // clock ticks after boot
};

// /proc/<pid>/stat: the state (field 3) and start time (field 22) of a process. The start time tells
// a lock's process from a later one that was given the same pid. nullopt when it cannot be read.
std::optional<ProcessStat> readProcessStat(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  if (!std::getline(in, stat)) return std::nullopt;
  const auto afterName = stat.rfind(')');  // the command name may hold spaces and parentheses
  if (afterName == std::string::npos) return std::nullopt;
  std::istringstream fields(stat.substr(afterName + 1));
  ProcessStat result;
  std::string field;
  for (int index = 3; index <= 22 && (fields >> field); ++index) {
    if (index == 3) result.finished = field == "Z" || field == "X";
    if (index == 22) {
      result.startTicks = std::stoll(field);
      return result;
    }
  }
  return std::nullopt;
}

// Whether process `pid` of this host still runs (and is the one that started at `startTicks`, when given).
bool processRuns(pid_t pid, std::optional<long long> startTicks) {
  if (pid <= 0 || (::kill(pid, 0) != 0 && errno == ESRCH)) return false;
  const auto stat = readProcessStat(pid);
  if (!stat) return true;  // it exists and /proc says no more: assume it is the one
  return !stat->finished && (!startTicks || *startTicks == stat->startTicks);
}

// Whether some job index below jobCount belongs to both shards (job i is in shard (i mod N) + 1).
bool shardsShareJobs(const Shard& a, const Shard& b, std::size_t jobCount) {
  for (std::size_t i = 0; i < jobCount; ++i) {
    if (static_cast<int>(i % static_cast<std::size_t>(a.count)) + 1 == a.index &&
        static_cast<int>(i % static_cast<std::size_t>(b.count)) + 1 == b.index) {
      return true;
    }
  }
  return false;
}

std::string shardText(const Shard& shard) { return std::to_string(shard.index) + "/" + std::to_string(shard.count); }

std::string utcNow() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  ::gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// flock(2) of the directory itself for as long as this object lives.
class DirectoryFlock {
public:
  explicit DirectoryFlock(const std::filesystem::path& directory)
      : fd_(::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ < 0) throw Error("cannot open " + directory.string() + ": " + std::strerror(errno));
    while (::flock(fd_, LOCK_EX) != 0) {
      if (errno != EINTR) {
        const int error = errno;
        ::close(fd_);
        throw Error("cannot lock " + directory.string() + ": " + std::strerror(error));
      }
    }
  }
  DirectoryFlock(const DirectoryFlock&) = delete;
  DirectoryFlock& operator=(const DirectoryFlock&) = delete;
  ~DirectoryFlock() { ::close(fd_); }  // releases the flock

private:
  int fd_;
};

struct LockHolder {
  pid_t pid = 0;
  std::string host;
  Shard shard;
  std::string started;
  std::optional<long long> startTicks;

  std::string describe(const std::filesystem::path& file) const {
    return "pid " + std::to_string(pid) + " on host " + host + " (shard " + shardText(shard) + ", started " + started +
           ", lock file " + file.string() + ")";
  }
};

LockHolder readLock(const std::filesystem::path& file) {
  try {
    std::ifstream in(file);
    const auto json = nlohmann::json::parse(in);
    LockHolder holder;
    holder.pid = json.at("pid").get<pid_t>();
    holder.host = json.at("host").get<std::string>();
    holder.shard = parseShard(json.at("shard").get<std::string>());
    holder.started = json.at("started_utc").get<std::string>();
    if (json.contains("process_start_ticks")) holder.startTicks = json.at("process_start_ticks").get<long long>();
    return holder;
  } catch (const std::exception& e) {
    throw Error(file.string() + ": not a campaign lock file (" + e.what() + "); if no campaign is running on " +
                file.parent_path().string() + ", delete it");
  }
}

bool isLockFile(const std::filesystem::path& file) {
  const auto name = file.filename().string();
  return name.rfind("campaign-", 0) == 0 && file.extension() == ".lock";
}

}  // namespace

OutputDirectoryLock::OutputDirectoryLock(const std::filesystem::path& directory, const Shard& shard,
                                         std::size_t jobCount, std::vector<std::string>& notes)
    : file_(directory / ("campaign-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".lock")),
      owner_(::getpid()) {
  const DirectoryFlock exclusive(directory);
  const std::string host = hostName();
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    if (!entry.is_regular_file() || !isLockFile(entry.path())) continue;
    const LockHolder holder = readLock(entry.path());
    if (holder.host == host && !processRuns(holder.pid, holder.startTicks)) {
      std::error_code ignored;
      std::filesystem::remove(entry.path(), ignored);
      notes.push_back("took over the lock of a campaign that is no longer running: " + holder.describe(entry.path()));
      continue;
    }
    if (holder.host == host && holder.pid == owner_) continue;  // (a lock this process holds already)
    if (shardsShareJobs(shard, holder.shard, jobCount)) {
      throw Error(directory.string() + " is in use by another campaign: " + holder.describe(entry.path()) +
                  "; wait for it to finish" +
                  (holder.host == host
                       ? std::string()
                       : " (if that process is gone from host " + holder.host + ", delete the lock file)"));
    }
    if (holder.host != host) otherHosts_.push_back(holder.host);
  }
  nlohmann::json lock{{"pid", owner_}, {"host", host}, {"shard", shardText(shard)}, {"started_utc", utcNow()}};
  if (const auto stat = readProcessStat(owner_)) lock["process_start_ticks"] = stat->startTicks;
  writeFileAtomically(file_, lock.dump(2) + "\n");
}

OutputDirectoryLock::~OutputDirectoryLock() {
  if (::getpid() != owner_) return;
  std::error_code ignored;
  std::filesystem::remove(file_, ignored);
}

std::vector<std::filesystem::path> removeAbandonedTemporaries(const std::filesystem::path& directory) {
  // AtomicOutputFile's "<target>.tmp.<pid>", and what SQLite adds to the database's temporary.
  static const std::regex temporaryName(R"(.*\.tmp\.([0-9]+)(-journal|-wal|-shm)?)");
  std::vector<std::filesystem::path> removed;
  std::error_code ec;
  for (auto entry = std::filesystem::recursive_directory_iterator(directory, ec);
       !ec && entry != std::filesystem::recursive_directory_iterator(); entry.increment(ec)) {
    std::smatch match;
    const std::string name = entry->path().filename().string();
    if (!entry->is_regular_file() || !std::regex_match(name, match, temporaryName)) continue;
    const auto pid = std::stoll(match[1].str());
    if (pid > 0 && pid < (1LL << 31) && processRuns(static_cast<pid_t>(pid), std::nullopt)) continue;
    std::error_code ignored;
    if (std::filesystem::remove(entry->path(), ignored)) removed.push_back(entry->path());
  }
  std::sort(removed.begin(), removed.end());
  return removed;
}

}  // namespace arcplan::benchmarks::detail
