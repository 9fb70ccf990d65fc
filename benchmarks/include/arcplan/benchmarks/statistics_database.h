#pragma once
// The benchmark database is made by the OMPL world's own tool, Debian's `ompl_benchmark_statistics`
// (package ompl-demos), from OMPL benchmark logs, so Planner Arena and other OMPL tooling read it too.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace arcplan::benchmarks {

// $ARCPLAN_OMPL_BENCHMARK_STATISTICS, else ompl_benchmark_statistics on PATH, else /usr/bin's.
// Throws arcplan::Error saying which package to install when none is found.
std::filesystem::path findBenchmarkStatisticsScript();

// Every *.log file below the given directories (recursively) or given directly, sorted by path.
// Throws arcplan::Error for a path that does not exist.
std::vector<std::filesystem::path> findLogs(const std::vector<std::filesystem::path>& paths);

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

// Runs ompl_benchmark_statistics on `logs` (in batches, appending) into a temporary file that replaces
// `database` only when every batch succeeded. Every log is checked first (benchmarkLogProblem): an
// incomplete one is never given to the script. Throws arcplan::Error naming each bad log and why, or
// with the script's output when it fails.
void buildBenchmarkDatabase(const std::vector<std::filesystem::path>& logs, const std::filesystem::path& database);

}  // namespace arcplan::benchmarks
