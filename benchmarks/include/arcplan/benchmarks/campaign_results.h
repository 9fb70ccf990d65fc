#pragma once
// A campaign's results per (problem, planner) pair as `bench compare` and baselines compare them: run
// and success counts, the metric values of the successful runs, the settings the logs recorded and
// the median run. Read from a campaign folder, a benchmark database or a baseline file.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "arcplan/benchmarks/run_record.h"

namespace arcplan::benchmarks {

// One planner configuration on one problem, as one campaign recorded it.
struct PlannerResults {
  int runs = 0;
  int successes = 0;
  std::map<std::string, std::vector<double>> values;  // metric key -> values of the successful runs
  PairSettings settings;                              // see BenchmarkDatabase::settings
  std::filesystem::path medianRun;                    // median-run CSV (paths/), empty when none
};

struct CampaignResults {
  std::string source;                // the folder or file it was read from, for the report
  PerPair<PlannerResults> problems;  // problem -> planner -> results
};

// A campaign folder (its benchmark.db and paths/), a benchmark database, or a baseline file
// (baseline.h). Throws arcplan::Error naming the file when it is none of these.
CampaignResults loadCampaignResults(const std::filesystem::path& campaignDatabaseOrBaseline);
// Runs (a success is RunRecord::succeeded(), the ranking's rule) plus their settings, without median runs.
CampaignResults campaignResultsFromRuns(const std::string& source, const CampaignRuns& runs,
                                        const PerPair<PairSettings>& settings = {});

}  // namespace arcplan::benchmarks
