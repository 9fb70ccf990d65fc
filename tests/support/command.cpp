#include "support/command.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace arcplan::testing {

namespace {

// Every directory a test process made is removed when it exits, unless ARCPLAN_KEEP_TEST_FILES is set
// (to look at what a failing test wrote).
struct TemporaryDirectories {
  std::vector<std::filesystem::path> created;
  ~TemporaryDirectories() {
    if (std::getenv("ARCPLAN_KEEP_TEST_FILES") != nullptr) return;
    std::error_code ignored;
    for (const auto& dir : created) std::filesystem::remove_all(dir, ignored);
  }
};

}  // namespace

std::filesystem::path freshTempDirectory(const std::string& name) {
  static TemporaryDirectories directories;
  const auto dir = std::filesystem::temp_directory_path() / ("arcplan_test_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  directories.created.push_back(dir);
  return dir;
}

std::string readFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

CommandResult runArcplan(const std::vector<std::string>& arguments,
                         const std::vector<std::pair<std::string, std::string>>& environment) {
  static int counter = 0;
  const auto dir = freshTempDirectory("cmd" + std::to_string(counter++));
  const auto outFile = dir / "stdout", errFile = dir / "stderr";
  const pid_t pid = fork();
  if (pid == 0) {
    for (const auto& [name, value] : environment) setenv(name.c_str(), value.c_str(), 1);
    std::vector<char*> argv;
    std::string executable = ARCPLAN_EXECUTABLE;
    argv.push_back(executable.data());
    std::vector<std::string> copies = arguments;
    for (auto& a : copies) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (!freopen(outFile.c_str(), "w", stdout) || !freopen(errFile.c_str(), "w", stderr)) _exit(126);
    execv(executable.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  CommandResult result;
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = readFile(outFile);
  result.err = readFile(errFile);
  std::filesystem::remove_all(dir);
  return result;
}

std::filesystem::path sharedDataDirectory() {
  const char* fromEnvironment = std::getenv("ARCPLAN_SHARED_DATA");
  const std::filesystem::path dir = fromEnvironment != nullptr ? fromEnvironment : ARCPLAN_SHARED_DATA_DIR;
  return std::filesystem::exists(dir) ? dir : std::filesystem::path();
}

std::vector<std::filesystem::path> filesBelow(const std::filesystem::path& root, const std::string& extension) {
  std::vector<std::filesystem::path> files;
  if (!std::filesystem::exists(root)) return files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (entry.is_regular_file() && (extension.empty() || entry.path().extension() == extension))
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::filesystem::path> temporaryFilesBelow(const std::filesystem::path& root) {
  std::vector<std::filesystem::path> temporaries;
  for (const auto& file : filesBelow(root)) {
    if (file.filename().string().find(".tmp") != std::string::npos) temporaries.push_back(file);
  }
  return temporaries;
}

}  // namespace arcplan::testing
