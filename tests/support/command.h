#pragma once
// Runs the real `arcplan` executable from tests: exit code, stdout and stderr, so command-line
// behaviour (messages, exit codes, files written) is tested end to end.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace arcplan::testing {

struct CommandResult {
  int exitCode = -1;
  std::string out;
  std::string err;
};

CommandResult runArcplan(const std::vector<std::string>& arguments,
                         const std::vector<std::pair<std::string, std::string>>& environment = {});

// A fresh, empty directory under the system temp folder, unique per test process and name; removed
// when the process exits (kept when ARCPLAN_KEEP_TEST_FILES is set).
std::filesystem::path freshTempDirectory(const std::string& name);

std::string readFile(const std::filesystem::path& file);

// Regular files below `root` (recursively; none if it does not exist), sorted; only those ending in
// `extension` when it is given.
std::vector<std::filesystem::path> filesBelow(const std::filesystem::path& root, const std::string& extension = "");
// Files below `root` with ".tmp" in their name: what an interrupted atomic write leaves.
std::vector<std::filesystem::path> temporaryFilesBelow(const std::filesystem::path& root);

// $ARCPLAN_SHARED_DATA or the configured ../shared/data; empty if it does not exist.
std::filesystem::path sharedDataDirectory();

}  // namespace arcplan::testing
