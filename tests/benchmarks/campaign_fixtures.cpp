#include "benchmarks/campaign_fixtures.h"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "support/command.h"
#include "support/database_rows.h"

namespace arcplan::testing {
namespace {

// Columns whose values depend on the machine and its load, not on the planner's decisions.
const std::set<std::string> kMeasuredColumns{"id",     "experimentid",        "plannerid", "time",
                                             "memory", "simplification_time", "solve_time"};

}  // namespace

std::filesystem::path writeTinySuite(const std::filesystem::path& directory, const std::vector<std::string>& planners,
                                     unsigned runs, unsigned budget) {
  const auto file = directory / "tiny.yaml";
  std::ofstream out(file);
  out << "name: tiny\nruns: " << runs << "\ntime_limit: 20\nbudget: " << budget
      << "\nv_max: 0.25\ngenerate: {seed: 20240611, line_obstacles: 1, pillars: 1, shelves: 0}\nplanners:\n";
  for (const auto& planner : planners) {
    if (planner == "arc-auto") {
      out << "  - {name: arc-auto, planner: arc, params: {auto: 1}}\n";
    } else {
      out << "  - " << planner << "\n";
    }
  }
  return file;
}

std::vector<std::string> benchArguments(const std::filesystem::path& suite, const std::filesystem::path& out,
                                        const std::vector<std::string>& extra) {
  std::vector<std::string> arguments{"bench",   "--suite", suite.string(), "--no-plots",
                                     "--quiet", "--out",   out.string()};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return arguments;
}

ArcplanProcess::ArcplanProcess(const std::vector<std::string>& arguments, std::optional<long> fileSizeLimit) {
  static int counter = 0;
  const auto dir = freshTempDirectory("process" + std::to_string(counter++));
  errFile_ = dir / "stderr";
  const auto outFile = dir / "stdout";
  pid_ = ::fork();
  if (pid_ == 0) {
    if (fileSizeLimit) {
      const rlimit limit{static_cast<rlim_t>(*fileSizeLimit), static_cast<rlim_t>(*fileSizeLimit)};
      if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) _exit(125);
    }
    std::string executable = ARCPLAN_EXECUTABLE;
    std::vector<std::string> copies = arguments;
    std::vector<char*> argv{executable.data()};
    for (auto& argument : copies) argv.push_back(argument.data());
    argv.push_back(nullptr);
    if (!std::freopen(outFile.c_str(), "w", stdout) || !std::freopen(errFile_.c_str(), "w", stderr)) _exit(126);
    ::execv(executable.c_str(), argv.data());
    _exit(127);
  }
}

ArcplanProcess::~ArcplanProcess() {
  if (pid_ > 0 && !exitCode_) {
    ::kill(pid_, SIGKILL);
    wait();
  }
}

bool ArcplanProcess::running() {
  if (exitCode_) return false;
  int status = 0;
  if (::waitpid(pid_, &status, WNOHANG) != pid_) return true;
  exitCode_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return false;
}

int ArcplanProcess::wait() {
  if (!exitCode_) {
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    exitCode_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  return *exitCode_;
}

std::string ArcplanProcess::err() const { return readFile(errFile_); }

std::vector<pid_t> ArcplanProcess::children() const {
  std::vector<pid_t> found;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const auto name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "stat");
    std::string stat;
    if (!std::getline(in, stat) || stat.rfind(')') == std::string::npos) continue;
    std::istringstream fields(stat.substr(stat.rfind(')') + 1));
    std::string state;
    pid_t parent = 0;
    if (fields >> state >> parent && parent == pid_) found.push_back(std::stoi(name));
  }
  return found;
}

bool processGone(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  if (!std::getline(in, stat) || stat.rfind(')') == std::string::npos) return true;
  std::istringstream fields(stat.substr(stat.rfind(')') + 1));
  std::string state;
  fields >> state;
  return state == "Z" || state == "X";
}

pid_t deadPid() {
  const pid_t child = ::fork();
  if (child == 0) _exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

std::vector<std::string> deterministicRuns(const std::filesystem::path& database) {
  std::vector<std::string> runs;
  // By name: ompl_benchmark_statistics adds columns in the order it meets them.
  std::set<std::string> names;
  for (const auto& row : databaseRows(database, "PRAGMA table_info(runs)")) {
    if (kMeasuredColumns.count(row[1]) == 0) names.insert(row[1]);
  }
  std::string columns;
  for (const auto& name : names) columns += ", r." + name;
  const auto rows =
      databaseRows(database, "SELECT e.name, p.name" + columns +
                                 " FROM runs r JOIN experiments e ON e.id = r.experimentid"
                                 " JOIN plannerConfigs p ON p.id = r.plannerid ORDER BY e.name, p.name, r.id");
  for (const auto& row : rows) {
    std::string text;
    for (const auto& value : row) text += value + "|";
    runs.push_back(text);
  }
  return runs;
}

}  // namespace arcplan::testing
