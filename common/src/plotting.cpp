#include "arcplan/common/plotting.h"

#include <cstdlib>
#include <mutex>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include "arcplan/common/resources.h"

extern char** environ;

namespace arcplan {
namespace {

// Runs argv[0] with argv, stdout/stderr inherited; returns the exit status or -1.
int runProcess(const std::vector<std::string>& argv, bool quiet) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet) {
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  }
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

std::optional<std::string> findMatplotlibPython() {
  static std::once_flag once;
  static std::optional<std::string> found;
  std::call_once(once, [] {
    std::vector<std::string> candidates;
    if (const char* chosen = std::getenv("ARCPLAN_PYTHON"); chosen != nullptr && *chosen != '\0') {
      candidates.emplace_back(chosen);
    }
    candidates.emplace_back("/usr/bin/python3");
    candidates.emplace_back("python3");
    for (const auto& python : candidates) {
      if (runProcess({python, "-c", "import matplotlib"}, true) == 0) {
        found = python;
        return;
      }
    }
  });
  return found;
}

PlotOutcome runPlotScript(const std::string& script, const std::vector<std::string>& arguments) {
  const auto python = findMatplotlibPython();
  if (!python) {
    return {false, "no Python with matplotlib found (install python3-matplotlib or set ARCPLAN_PYTHON); plot skipped"};
  }
  const auto path = plotScriptDirectory() / script;
  std::vector<std::string> argv{*python, path.string()};
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  const int status = runProcess(argv, false);
  if (status != 0) return {false, "plot script " + path.string() + " failed (exit " + std::to_string(status) + ")"};
  return {true, {}};
}

}  // namespace arcplan
