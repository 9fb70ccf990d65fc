#pragma once
// One benchmark run as arcplan reads it back (benchmark_database.h, baseline.h), and the keys runs
// are grouped by: the problem (OMPL experiment name) and the planner (configuration label).
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace arcplan::benchmarks {

using ProblemName = std::string;   // OMPL experiment name, "<suite>/<problem>": "thesis/obstacle"
using PlannerLabel = std::string;  // configuration label, OMPL's "geometric_"/"control_" prefix removed

struct RunRecord {
  // OMPL's `solved`: an exact solution (arcplan withdraws it for a path that came closer than the
  // suite's clearance).
  bool solved = false;
  // Recorded values by key: metric keys of trajectory/metric_descriptors.h ("execution_time_s") for
  // arcplan's runs, column names ("time") for a plain OMPL database; absent = not recorded (NULL).
  std::map<std::string, double> values;

  // The ranking's success: solved and time-scaled (it has a finite execution time).
  bool succeeded() const;
  // The value under `key` when recorded and finite.
  std::optional<double> value(const std::string& key) const;
};

// Something per (problem, planner) pair: problem -> planner -> T.
template <class T>
using PerPair = std::map<ProblemName, std::map<PlannerLabel, T>>;
// Every run of a campaign, per pair in the order they ran.
using CampaignRuns = PerPair<std::vector<RunRecord>>;
// Setting name -> value, as one pair's logs recorded them (BenchmarkDatabase::settings).
using PairSettings = std::map<std::string, std::string>;

}  // namespace arcplan::benchmarks
