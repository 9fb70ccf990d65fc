#pragma once
// Whether an OMPL benchmark log is complete: what a campaign checks before it counts a job as done
// and before it gives a log to ompl_benchmark_statistics (statistics_database.h).
#include <filesystem>
#include <optional>
#include <string>

namespace arcplan::benchmarks {

// What a campaign job's log must hold; an empty name or zero runs is not checked.
struct LogExpectation {
  std::string experiment;  // "<suite>/<problem>"
  std::string planner;     // the planner's label (the log says "geometric_<label>")
  unsigned runs = 0;
};

// Why `log` is not a complete OMPL benchmark log ("line 212: 7 of 10 runs, then the file ends"), or
// nullopt when it is. Reads the structure ompl_benchmark_statistics reads (header, setup block, counts,
// one line per run with one value per property, the closing "."), so a log cut short by a crash or a
// full disk, or garbled, is caught here: the script itself would store a cut run as a row of NULLs.
std::optional<std::string> benchmarkLogProblem(const std::filesystem::path& log, const LogExpectation& expected = {});

}  // namespace arcplan::benchmarks
