#include "arcplan/common/process.h"

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace arcplan {

ProcessResult runProcess(const std::vector<std::string>& argv, ProcessOutput output) {
  ProcessResult result;
  if (argv.empty()) return result;
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  // Captured output goes through a file: no pipe to drain while waiting, however much is written.
  static std::atomic<unsigned> calls{0};
  const auto captureFile = std::filesystem::temp_directory_path() /
                           ("arcplan_process_" + std::to_string(::getpid()) + "_" + std::to_string(calls++));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (output == ProcessOutput::Discard) {
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  } else if (output == ProcessOutput::Capture) {
    posix_spawn_file_actions_addopen(&actions, 1, captureFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
  }
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    result.output = "cannot start " + argv[0];
    return result;
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) break;
  }
  if (WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
  if (output == ProcessOutput::Capture) {
    std::ifstream in(captureFile);
    std::ostringstream text;
    text << in.rdbuf();
    result.output = text.str();
    std::error_code ignored;
    std::filesystem::remove(captureFile, ignored);
  }
  return result;
}

}  // namespace arcplan
