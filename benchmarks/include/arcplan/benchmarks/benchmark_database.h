#pragma once
// The one reader of a benchmark database (benchmark.db, the SQLite file Debian's
// ompl_benchmark_statistics builds from OMPL logs, possibly merged from many shards), for the ranking,
// `bench compare`, baselines and the HTML report. arcplan's databases give every run's metrics under
// their keys (trajectory/metric_descriptors.h); a plain OMPL database its numeric run columns.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arcplan/benchmarks/run_record.h"

namespace arcplan::benchmarks {

// What RunRecord::values hold: a metric ("execution_time_s", "execution time (s)") or a column.
struct RunAttribute {
  std::string key;
  std::string label;
};

struct BenchmarkDatabase {
  std::filesystem::path file;
  bool arcplanColumns = false;                  // the runs table has arcplan's metric columns (execution_time)
  std::vector<RunAttribute> attributes;         // the metric table's metrics present, or every numeric run column
  CampaignRuns runs;                            // in database order
  std::map<ProblemName, std::string> families;  // problem -> family, where the experiments name one
  // Per pair, as the logs recorded them: "runs", "time limit (s)", "vmax (m/s)", "clearance (m)",
  // iteration budget, seeds, library versions, host, and "parameter <name>" for each planner parameter
  // (OMPL's projection cell sizes left out: OMPL derives them from random samples). Settings that differ
  // between the jobs of one pair (merged shards) are joined with " | ".
  PerPair<PairSettings> settings;
  nlohmann::json experiments = nlohmann::json::array();  // every experiments row, column -> value
};

// A campaign folder's benchmark.db, or `folderOrDatabase` itself when it is not a folder. Throws arcplan::Error
// naming the folder when it has no benchmark.db (`bench` writes it once every job of the campaign is done).
std::filesystem::path campaignDatabase(const std::filesystem::path& folderOrDatabase);

// Throws arcplan::Error if the file is missing, is not an OMPL benchmark database (no
// runs/experiments/plannerConfigs tables) or holds no runs.
BenchmarkDatabase readBenchmarkDatabase(const std::filesystem::path& file);

}  // namespace arcplan::benchmarks
