#include "arcplan/benchmarks/statistics_database.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "arcplan/common/error.h"

extern char** environ;

namespace arcplan::benchmarks {
namespace {

// Command-line length stays far below ARG_MAX with this many log paths per call.
constexpr std::size_t kLogsPerCall = 200;

bool isExecutable(const std::filesystem::path& file) {
  return std::filesystem::is_regular_file(file) && ::access(file.c_str(), X_OK) == 0;
}

struct ProcessResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr interleaved
};

// Runs argv without a shell, capturing its output in a temporary file (the script prints one line
// per log file; we show it only when something goes wrong).
ProcessResult runCapturing(const std::vector<std::string>& argv, const std::filesystem::path& outputFile) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, outputFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ProcessResult result;
  if (spawned != 0) {
    result.output = "cannot start " + argv[0];
    return result;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return result;
  }
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(outputFile);
  std::ostringstream text;
  text << in.rdbuf();
  result.output = text.str();
  std::error_code ignored;
  std::filesystem::remove(outputFile, ignored);
  return result;
}

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
  throw Error("ompl_benchmark_statistics not found (it builds the benchmark database from the OMPL logs): install "
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
  const auto script = findBenchmarkStatisticsScript();
  if (database.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(database.parent_path(), ec);
    if (ec) throw Error("cannot create directory " + database.parent_path().string() + ": " + ec.message());
  }
  auto temporary = database;
  temporary += ".tmp." + std::to_string(::getpid());
  auto scriptOutput = database;
  scriptOutput += ".output." + std::to_string(::getpid());
  std::error_code ignored;
  std::filesystem::remove(temporary, ignored);
  for (std::size_t first = 0; first < logs.size(); first += kLogsPerCall) {
    std::vector<std::string> argv{script.string(), "-d", temporary.string()};
    if (first > 0) argv.emplace_back("-a");
    const auto last = std::min(logs.size(), first + kLogsPerCall);
    for (std::size_t i = first; i < last; ++i) argv.push_back(logs[i].string());
    const auto result = runCapturing(argv, scriptOutput);
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
