#pragma once
// Ranking of planners from a benchmark database (the SQLite file ompl_benchmark_statistics builds from
// OMPL logs, possibly merged from many shards).
//
// Per problem (OMPL experiment name), planners are ordered by
//   1. success rate (exact solution whose metrics could be computed), higher first;
//   2. median execution time after PCHIP scaling over ALL runs, a failed run counting as +inf
//      (so the median is finite only when more than half of the runs succeed: a planner that solves
//      2 of 100 runs never wins on the median of its 2 successes), shorter first.
// Planners equal in both keys share a rank (1, 2, 2, 4, ...); planners with no success share the
// last rank. The overall rank orders planners by their mean rank over the problems they ran on.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arcplan/benchmarks/run_record.h"
#include "arcplan/trajectory/metric_descriptors.h"

namespace arcplan::benchmarks {

// The metrics the ranking summarises: every trajectory metric, as the metric table lists them (its
// JSON key, label and database columns; trajectory/metric_descriptors.h, docs/metrics.md).
using RankedMetric = trajectory::MetricDescriptor;
const std::vector<RankedMetric>& rankedMetrics();

// Statistics of one metric over the successful runs; count == 0 means no successful run (values NaN).
struct MetricSummary {
  int count = 0;
  double median = 0.0, mean = 0.0, min = 0.0, max = 0.0;
};

struct PlannerStanding {
  std::string planner;  // configuration label ("arc-h0.75r"; OMPL's "geometric_" prefix removed)
  int rank = 0;
  int runs = 0;
  int successes = 0;
  double successRate = 0.0;
  double medianExecutionTime = 0.0;              // over all runs, failures as +inf (see above)
  std::map<std::string, MetricSummary> metrics;  // by RankedMetric::key, over successful runs
  // Overall standing only:
  double meanRank = 0.0;
  int problems = 0;     // problems this planner ran on
  int firstPlaces = 0;  // problems where it ranked 1
};

struct ProblemRanking {
  std::string problem;                    // experiment name ("thesis/obstacle")
  std::vector<PlannerStanding> planners;  // best first
};

// The overall standing restricted to one problem family ("pillar", "line-box", ...): mean rank and
// pooled success over the family's problems, so losses on one kind of scene stay visible.
struct FamilyRanking {
  std::string family;
  int problems = 0;
  std::vector<PlannerStanding> planners;  // best first
};

struct Ranking {
  std::filesystem::path database;
  std::vector<ProblemRanking> problems;  // in name order
  std::vector<PlannerStanding> overall;  // best first
  std::vector<FamilyRanking> families;   // when problems name their family and there are several
  int problemCount() const { return static_cast<int>(problems.size()); }
};

// Reads every run of the database (benchmark_database.h). Throws arcplan::Error if the file is
// missing, is not an OMPL benchmark database or holds no runs.
Ranking rankDatabase(const std::filesystem::path& database);

// Rank planners from per-run data (what rankDatabase does after reading); a run counts as a success
// when RunRecord::succeeded(). `families` maps problems to their family (the experiments'
// `problemkind` column in a database).
Ranking rankRuns(const CampaignRuns& runs, const std::map<ProblemName, std::string>& families = {});

std::string rankingMarkdown(const Ranking& ranking);
nlohmann::json rankingJson(const Ranking& ranking);
std::string rankingCsv(const Ranking& ranking);
// The overall table, success by problem family, and the per-problem tables when there are at most
// `maxProblemTables` problems.
std::string rankingTerminalTable(const Ranking& ranking, int maxProblemTables = 4);

// ranking.md, ranking.json and ranking.csv in `directory`, each written atomically.
void writeRanking(const Ranking& ranking, const std::filesystem::path& directory);

}  // namespace arcplan::benchmarks
