#pragma once
// Running another program (matplotlib scripts, Debian's ompl_benchmark_statistics) without a shell:
// the arguments go to it as they are, whatever characters file names contain.
#include <string>
#include <vector>

namespace arcplan {

enum class ProcessOutput {
  Inherit,  // the program writes to our stdout and stderr
  Discard,  // to /dev/null
  Capture,  // into ProcessResult::output (stdout and stderr interleaved)
};

struct ProcessResult {
  int exitCode = -1;  // -1 when it could not be started or did not exit normally
  std::string output;
};

// argv[0] is looked up on PATH unless it contains a '/'. Waits for the program to end.
ProcessResult runProcess(const std::vector<std::string>& argv, ProcessOutput output = ProcessOutput::Inherit);

}  // namespace arcplan
