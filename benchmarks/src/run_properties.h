#pragma once
// Names that cross from the benchmark logs arcplan writes (job_runner.cpp) through Debian's
// ompl_benchmark_statistics into the database arcplan reads back (benchmark_database.cpp). The metric
// run properties are in trajectory/metric_descriptors.h; this holds the others that are read back.
// Internal to arcplan::benchmarks.
#include <algorithm>
#include <string>

namespace arcplan::benchmarks {

struct ExperimentParameter {
  const char* name;  // as in the log: only [A-Za-z0-9 ] (the statistics script pastes it into SQL)
  const char* type;  // SQL type
};

// The problem family ("line-sphere", "pillar", "scene file"): the ranking's per-family tables.
inline constexpr ExperimentParameter kProblemKindParameter{"problem kind", "TEXT"};

// ompl_benchmark_statistics drops the blanks of experiment parameter names ("problemkind"), while
// it joins the words of run property names with '_' ("tcp_path_length").
inline std::string databaseColumn(const ExperimentParameter& parameter) {
  std::string column = parameter.name;
  column.erase(std::remove(column.begin(), column.end(), ' '), column.end());
  return column;
}

}  // namespace arcplan::benchmarks
