#include "arcplan/benchmarks/statistics_database.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "arcplan/benchmarks/benchmark_log_check.h"
#include "arcplan/common/error.h"
#include "arcplan/common/process.h"

namespace arcplan::benchmarks {
namespace {

// Command-line length stays far below ARG_MAX with this many log paths per call.
constexpr std::size_t kLogsPerCall = 200;

bool isExecutable(const std::filesystem::path& file) {
  return std::filesystem::is_regular_file(file) && ::access(file.c_str(), X_OK) == 0;
}

// Bad logs named in one error message; more are counted.
constexpr std::size_t kBadLogsNamed = 10;

// What is wrong with a log, at the line where it was found.
}  // namespace

std::filesystem::path findBenchmarkStatisticsScript() {
  if (const char* chosen = std::getenv("ARCPLAN_OMPL_BENCHMARK_STATISTICS"); chosen != nullptr && *chosen != '\0') {
    if (!isExecutable(chosen)) {
      throw Error(std::string("ARCPLAN_OMPL_BENCHMARK_STATISTICS=") + chosen + " is not an executable file");
    }
    return chosen;
  }
  if (const char* path = std::getenv("PATH"); path != nullptr) {
    std::stringstream directories(path);
    std::string directory;
    while (std::getline(directories, directory, ':')) {
      const auto candidate = std::filesystem::path(directory.empty() ? "." : directory) / "ompl_benchmark_statistics";
      if (isExecutable(candidate)) return candidate;
    }
  }
  const std::filesystem::path debian = "/usr/bin/ompl_benchmark_statistics";
  if (isExecutable(debian)) return debian;
  throw Error(
      "ompl_benchmark_statistics not found (it builds the benchmark database from the OMPL logs): install "
      "Debian's ompl-demos package (scripts/setup) or set ARCPLAN_OMPL_BENCHMARK_STATISTICS");
}

std::vector<std::filesystem::path> findLogs(const std::vector<std::filesystem::path>& paths) {
  std::vector<std::filesystem::path> logs;
  for (const auto& path : paths) {
    if (std::filesystem::is_regular_file(path)) {
      logs.push_back(path);
    } else if (std::filesystem::is_directory(path)) {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(path)) {
        if (entry.is_regular_file() && entry.path().extension() == ".log") logs.push_back(entry.path());
      }
    } else {
      throw Error("log path " + path.string() + " does not exist");
    }
  }
  std::sort(logs.begin(), logs.end());
  logs.erase(std::unique(logs.begin(), logs.end()), logs.end());
  return logs;
}

void buildBenchmarkDatabase(const std::vector<std::filesystem::path>& logs, const std::filesystem::path& database) {
  if (logs.empty()) throw Error("no OMPL benchmark logs to put into " + database.string());
  std::vector<std::string> badLogs;
  for (const auto& log : logs) {
    if (const auto problem = benchmarkLogProblem(log)) badLogs.push_back(log.string() + ": " + *problem);
  }
  if (!badLogs.empty()) {
    std::string message = std::to_string(badLogs.size()) +
                          " incomplete or corrupt OMPL log(s), not given to "
                          "ompl_benchmark_statistics (" +
                          database.string() + " is unchanged):";
    for (std::size_t i = 0; i < std::min(badLogs.size(), kBadLogsNamed); ++i) message += "\n  " + badLogs[i];
    if (badLogs.size() > kBadLogsNamed)
      message += "\n  ... and " + std::to_string(badLogs.size() - kBadLogsNamed) + " more";
    throw Error(message + "\nrerun the campaign that wrote them (it runs their jobs again) or leave them out");
  }
  const auto script = findBenchmarkStatisticsScript();
  if (database.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(database.parent_path(), ec);
    if (ec) throw Error("cannot create directory " + database.parent_path().string() + ": " + ec.message());
  }
  auto temporary = database;
  temporary += ".tmp." + std::to_string(::getpid());
  std::error_code ignored;
  std::filesystem::remove(temporary, ignored);
  for (std::size_t first = 0; first < logs.size(); first += kLogsPerCall) {
    // setpriv (util-linux, always on Debian) makes the kernel kill the script when this process dies:
    // a script outliving a killed campaign would go on writing its temporary database after the
    // resumed campaign removed it.
    std::vector<std::string> argv{"setpriv", "--pdeathsig", "KILL", "--", script.string(), "-d", temporary.string()};
    if (first > 0) argv.emplace_back("-a");
    const auto last = std::min(logs.size(), first + kLogsPerCall);
    for (std::size_t i = first; i < last; ++i) argv.push_back(logs[i].string());
    const auto result = runProcess(argv, ProcessOutput::Capture);
    if (result.exitCode != 0) {
      std::filesystem::remove(temporary, ignored);
      throw Error(script.string() + " failed (exit " + std::to_string(result.exitCode) + ") on logs " +
                  logs[first].string() + " ... " + logs[last - 1].string() + ":\n" + result.output);
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, database, ec);
  if (ec) {
    std::filesystem::remove(temporary, ignored);
    throw Error("cannot move " + temporary.string() + " to " + database.string() + ": " + ec.message());
  }
}

}  // namespace arcplan::benchmarks
