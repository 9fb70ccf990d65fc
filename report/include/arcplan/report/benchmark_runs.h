#pragma once
// Every run of an OMPL benchmark database (built by ompl_benchmark_statistics), attribute by
// attribute, for the report's box plots — the per-run view Planner Arena gives. arcplan's own
// databases are read through the ranked metrics of benchmarks/ranking.h; a plain OMPL database
// gives its numeric run columns (time, memory, solution length, ...).
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace arcplan::report {

struct RunAttribute {
  std::string key;    // "execution_time_s" (arcplan metric) or the column name ("time")
  std::string label;  // "execution time (s)"
};

struct BenchmarkRun {
  int index = 0;  // 0-based within its (problem, planner), in database order
  bool solved = false;
  std::map<std::string, double> values;  // by RunAttribute::key; absent = NULL
};

struct BenchmarkRuns {
  bool arcplanColumns = false;  // the runs table has arcplan's execution_time column
  std::vector<RunAttribute> attributes;
  // problem (experiment name) -> planner (without OMPL's "geometric_" prefix) -> runs
  std::map<std::string, std::map<std::string, std::vector<BenchmarkRun>>> runs;
  nlohmann::json experiments = nlohmann::json::array();  // every experiments row, column -> value
};

// Throws arcplan::Error when the file is missing, is not an OMPL benchmark database, or has no runs.
BenchmarkRuns readBenchmarkRuns(const std::filesystem::path& database);

}  // namespace arcplan::report
