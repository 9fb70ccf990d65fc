#pragma once
// `arcplan bench compare`: did a planner get better or worse between two campaigns? Runs are matched
// by (problem, planner configuration label); per pair the success rate and each compared metric get
// a verdict (docs/benchmarks.md, "Comparing campaigns"):
//   - zero variance on both sides (every run the same, as the arc planner's): exact comparison
//     within a tolerance, and the first differing waypoint of the median runs when both campaigns
//     kept them;
//   - otherwise: Fisher's exact test (success) or the Mann-Whitney U test (metric values of the
//     successful runs), Holm-adjusted over the whole table; a row is better or worse only when the
//     adjusted p-value is below alpha AND the change is at least the minimum effect.
// Which way is better comes from the metric table (trajectory/metric_descriptors.h).
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arcplan/benchmarks/campaign_results.h"

namespace arcplan::benchmarks {

// The metrics compared unless told otherwise: execution time, TCP path length, solve time, minimum
// clearance and peak TCP speed (with the success rate, which is always compared).
const std::vector<std::string>& defaultComparedMetrics();
inline const std::string kSuccessRateKey = "success_rate";

struct ComparisonOptions {
  double alpha = 0.01;      // family-wise error rate of the stochastic tests (Holm)
  double minEffect = 0.05;  // relative median change / success-rate difference below which nothing is flagged
  double tolerance = 1e-6;  // exact comparison, in the metric's SI unit (m, s, ...)
  // Solve time is the machine's wall clock: changes of the median below this many seconds are never
  // flagged, since scheduling on a loaded machine moves sub-millisecond solve times by more than 5 %.
  double solveTimeFloor = 0.005;
  std::vector<std::string> metrics = defaultComparedMetrics();  // metric keys of the metric table
};

enum class Verdict { Better, Same, Worse, NotComparable };
std::string verdictName(Verdict verdict);  // "better", "same", "worse", "not comparable"

enum class ComparisonMethod { Exact, Fisher, MannWhitney, None };
std::string methodName(ComparisonMethod method);  // "exact", "Fisher", "Mann-Whitney U", "-"

struct ComparisonRow {
  std::string problem;
  std::string planner;
  std::string metric;  // kSuccessRateKey or a metric key
  ComparisonMethod method = ComparisonMethod::None;
  int baseCount = 0, newCount = 0;   // runs (success rate) or successful runs (metrics)
  double base = 0.0, current = 0.0;  // success rate, the exact value, or the median
  // Success rate: new - base. Metrics: relative change of the value / median, new / base - 1.
  double effect = 0.0;
  double pValue = std::numeric_limits<double>::quiet_NaN();          // stochastic tests only
  double adjustedPValue = std::numeric_limits<double>::quiet_NaN();  // Holm over every stochastic row
  // Mann-Whitney rows: rank-biserial correlation of new against base, in [-1, 1] (+1: every new value
  // above every base value), the effect size of the rank test.
  double rankBiserial = std::numeric_limits<double>::quiet_NaN();
  Verdict verdict = Verdict::NotComparable;
  std::string note;  // why not comparable, or where the paths first differ
};

struct SettingDifference {
  std::string setting;
  std::string base, current;       // "(none)" where one side did not record it
  std::vector<std::string> pairs;  // "problem · planner"; empty = every matched pair
};

struct CampaignComparison {
  std::string base, current;  // sources
  ComparisonOptions options;
  std::vector<std::string> onlyInBase, onlyInNew;  // "problem · planner"
  std::vector<SettingDifference> settings;
  std::vector<ComparisonRow> rows;  // problems, planners in name order; success first, then metrics
  int count(Verdict verdict) const;
  bool anyWorse() const { return count(Verdict::Worse) > 0; }
};

// Throws arcplan::Error naming the option for one out of range (alpha not in (0, 1), a negative
// effect, tolerance or floor) or an unknown metric key.
void checkComparisonOptions(const ComparisonOptions& options);

// Throws as checkComparisonOptions does.
CampaignComparison compareCampaigns(const CampaignResults& base, const CampaignResults& current,
                                    const ComparisonOptions& options = {});

std::string comparisonMarkdown(const CampaignComparison& comparison, bool onlyChanges = false);
nlohmann::json comparisonJson(const CampaignComparison& comparison);
std::string comparisonCsv(const CampaignComparison& comparison);
// comparison.md, comparison.json and comparison.csv in `directory`, each written atomically.
void writeComparison(const CampaignComparison& comparison, const std::filesystem::path& directory);

}  // namespace arcplan::benchmarks
