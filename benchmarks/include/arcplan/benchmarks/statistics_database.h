#pragma once
// The benchmark database is made by the OMPL world's own tool, Debian's `ompl_benchmark_statistics`
// (package ompl-demos), from OMPL benchmark logs, so Planner Arena and other OMPL tooling read it too.
// Whether a log is complete enough to give it to the script is benchmark_log_check.h.
#include <filesystem>
#include <string>
#include <vector>

namespace arcplan::benchmarks {

// $ARCPLAN_OMPL_BENCHMARK_STATISTICS, else ompl_benchmark_statistics on PATH, else /usr/bin's.
// Throws arcplan::Error saying which package to install when none is found.
std::filesystem::path findBenchmarkStatisticsScript();

// Every *.log file below the given directories (recursively) or given directly, sorted by path.
// Throws arcplan::Error for a path that does not exist.
std::vector<std::filesystem::path> findLogs(const std::vector<std::filesystem::path>& paths);

// Runs ompl_benchmark_statistics on `logs` (in batches, appending) into a temporary file that replaces
// `database` only when every batch succeeded. Every log is checked first (benchmarkLogProblem): an
// incomplete one is never given to the script. Throws arcplan::Error naming each bad log and why, or
// with the script's output when it fails.
void buildBenchmarkDatabase(const std::vector<std::filesystem::path>& logs, const std::filesystem::path& database);

}  // namespace arcplan::benchmarks
