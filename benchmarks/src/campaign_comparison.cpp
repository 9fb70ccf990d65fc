// bench compare: matching two campaigns' runs, the verdict of every (pair, metric) row, and the
// comparison tables (campaign_comparison.h).
#include "arcplan/benchmarks/campaign_comparison.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <tuple>

#include "arcplan/benchmarks/comparison_statistics.h"
#include "arcplan/benchmarks/median_run.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/trajectory/metric_descriptors.h"

namespace arcplan::benchmarks {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
std::string pairName(const ProblemName& problem, const PlannerLabel& planner) { return problem + " · " + planner; }

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return quantileOfSorted(values, 0.5);
}

bool zeroVariance(const std::vector<double>& values, double tolerance) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return *high - *low <= tolerance;
}

double relativeChange(double base, double current) {
  if (base == current) return 0.0;
  if (base == 0.0)
    return current > 0.0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
  return current / base - 1.0;
}

// A change in the good direction is better, in the other worse.
Verdict directionVerdict(double change, bool lowerIsBetter) {
  if (change == 0.0) return Verdict::Same;
  return (change < 0.0) == lowerIsBetter ? Verdict::Better : Verdict::Worse;
}

// ---- median runs: the first waypoint where two deterministic paths part ------------------------

// A median run's sample columns by name, the positions (x, y, z, q0..q5 when recorded) before the timing
// (t, tcp_speed): where paths part geometrically says more than where their timing does.
std::vector<std::pair<std::string, std::function<double(std::size_t)>>> sampleColumns(const MedianRun& run,
                                                                                      bool joints) {
  std::vector<std::pair<std::string, std::function<double(std::size_t)>>> columns;
  for (int k = 0; k < 3; ++k)
    columns.emplace_back(std::string(1, "xyz"[k]), [&run, k](std::size_t i) { return run.tcp[i][k]; });
  for (int j = 0; joints && j < 6; ++j) {
    columns.emplace_back("q" + std::to_string(j), [&run, j](std::size_t i) { return run.joints[i][j]; });
  }
  columns.emplace_back("t", [&run](std::size_t i) { return run.time[i]; });
  columns.emplace_back("tcp_speed", [&run](std::size_t i) { return run.tcpSpeed[i]; });
  return columns;
}

// "" when the paths agree within the tolerance; else where they first differ.
std::string firstPathDifference(const std::filesystem::path& baseFile, const std::filesystem::path& currentFile,
                                double tolerance) {
  const MedianRun base = readMedianRun(baseFile), current = readMedianRun(currentFile);
  const bool joints = !base.joints.empty() && !current.joints.empty();
  const auto baseColumns = sampleColumns(base, joints), currentColumns = sampleColumns(current, joints);
  const std::size_t rows = std::min(base.time.size(), current.time.size());
  for (const auto& [begin, end] :
       {std::pair<std::size_t, std::size_t>{0, baseColumns.size() - 2}, {baseColumns.size() - 2, baseColumns.size()}}) {
    for (std::size_t r = 0; r < rows; ++r) {
      for (std::size_t c = begin; c < end; ++c) {
        const double b = baseColumns[c].second(r), n = currentColumns[c].second(r);
        if (std::abs(b - n) <= tolerance) continue;
        return "median runs first differ at waypoint " + std::to_string(r) + ": " + baseColumns[c].first + " " +
               formatNumber(b, 9) + " -> " + formatNumber(n, 9);
      }
    }
  }
  if (base.time.size() != current.time.size()) {
    return "median runs agree on their first " + std::to_string(rows) + " waypoints, then have " +
           std::to_string(base.time.size()) + " -> " + std::to_string(current.time.size()) + " waypoints";
  }
  return "";
}

// ---- rows ------------------------------------------------------------------------------------

ComparisonRow newRow(const std::string& problem, const std::string& planner, const std::string& metric) {
  ComparisonRow row;
  row.problem = problem;
  row.planner = planner;
  row.metric = metric;
  return row;
}

ComparisonRow successRow(const std::string& problem, const std::string& planner, const PlannerResults& base,
                         const PlannerResults& current) {
  auto row = newRow(problem, planner, kSuccessRateKey);
  row.baseCount = base.runs;
  row.newCount = current.runs;
  if (base.runs == 0 || current.runs == 0) {
    row.base = row.current = kNaN;
    row.note = "no runs on one side";
    return row;
  }
  row.base = static_cast<double>(base.successes) / base.runs;
  row.current = static_cast<double>(current.successes) / current.runs;
  row.effect = row.current - row.base;
  const auto constant = [](const PlannerResults& r) { return r.successes == 0 || r.successes == r.runs; };
  if (constant(base) && constant(current)) {
    row.method = ComparisonMethod::Exact;
    row.verdict = directionVerdict(row.effect, false);
    return row;
  }
  row.method = ComparisonMethod::Fisher;
  row.pValue = fisherExactTwoSided(base.successes, base.runs - base.successes, current.successes,
                                   current.runs - current.successes);
  return row;
}

ComparisonRow metricRow(const std::string& problem, const std::string& planner,
                        const trajectory::MetricDescriptor& metric, const PlannerResults& base,
                        const PlannerResults& current, const ComparisonOptions& options) {
  auto row = newRow(problem, planner, metric.key);
  const auto valuesOf = [&](const PlannerResults& r) {
    const auto found = r.values.find(metric.key);
    return found == r.values.end() ? std::vector<double>{} : found->second;
  };
  const auto baseValues = valuesOf(base), currentValues = valuesOf(current);
  row.baseCount = static_cast<int>(baseValues.size());
  row.newCount = static_cast<int>(currentValues.size());
  if (baseValues.empty() || currentValues.empty()) {
    row.base = baseValues.empty() ? kNaN : median(baseValues);
    row.current = currentValues.empty() ? kNaN : median(currentValues);
    row.note = std::string("no successful run with this metric in ") + (baseValues.empty() ? "base" : "new");
    return row;
  }
  row.base = median(baseValues);
  row.current = median(currentValues);
  row.effect = relativeChange(row.base, row.current);
  if (zeroVariance(baseValues, options.tolerance) && zeroVariance(currentValues, options.tolerance)) {
    row.method = ComparisonMethod::Exact;
    const double change = row.current - row.base;
    row.verdict =
        std::abs(change) <= options.tolerance ? Verdict::Same : directionVerdict(change, metric.lowerIsBetter);
    return row;
  }
  row.method = ComparisonMethod::MannWhitney;
  const auto test = mannWhitneyU(currentValues, baseValues);
  row.pValue = test.pValue;
  row.rankBiserial = test.rankBiserial;
  return row;
}

// The verdict of a stochastic row once its p-value is adjusted: a significant change that is also
// large enough (and, for the solve time, beyond the clock's noise floor).
Verdict stochasticVerdict(const ComparisonRow& row, const ComparisonOptions& options) {
  if (!(row.adjustedPValue < options.alpha) || !(std::abs(row.effect) >= options.minEffect)) return Verdict::Same;
  if (row.method == ComparisonMethod::Fisher) return directionVerdict(row.effect, false);
  if (row.metric == trajectory::solveTimeDescriptor().key && std::abs(row.current - row.base) < options.solveTimeFloor)
    return Verdict::Same;
  return directionVerdict(row.current - row.base, trajectory::metricDescriptor(row.metric).lowerIsBetter);
}

void addSettingDifferences(
    const std::string& pair, const PlannerResults& base, const PlannerResults& current,
    std::map<std::tuple<std::string, std::string, std::string>, std::vector<std::string>>& found) {
  std::set<std::string> names;
  for (const auto& [name, value] : base.settings) names.insert(name);
  for (const auto& [name, value] : current.settings) names.insert(name);
  for (const auto& name : names) {
    const auto b = base.settings.find(name), c = current.settings.find(name);
    const std::string baseValue = b == base.settings.end() ? "(none)" : b->second;
    const std::string currentValue = c == current.settings.end() ? "(none)" : c->second;
    if (baseValue != currentValue) found[{name, baseValue, currentValue}].push_back(pair);
  }
}

}  // namespace

const std::vector<std::string>& defaultComparedMetrics() {
  using M = trajectory::TrajectoryMetrics;
  static const std::vector<std::string> keys{
      trajectory::metricDescriptor(&M::executionTime).key, trajectory::metricDescriptor(&M::tcpPathLength).key,
      trajectory::solveTimeDescriptor().key, trajectory::metricDescriptor(&M::minClearance).key,
      trajectory::metricDescriptor(&M::peakTcpSpeed).key};
  return keys;
}

std::string verdictName(Verdict verdict) {
  switch (verdict) {
    case Verdict::Better:
      return "better";
    case Verdict::Same:
      return "same";
    case Verdict::Worse:
      return "worse";
    case Verdict::NotComparable:
      break;
  }
  return "not comparable";
}

std::string methodName(ComparisonMethod method) {
  switch (method) {
    case ComparisonMethod::Exact:
      return "exact";
    case ComparisonMethod::Fisher:
      return "Fisher";
    case ComparisonMethod::MannWhitney:
      return "Mann-Whitney U";
    case ComparisonMethod::None:
      break;
  }
  return "-";
}

int CampaignComparison::count(Verdict verdict) const {
  return static_cast<int>(
      std::count_if(rows.begin(), rows.end(), [&](const ComparisonRow& row) { return row.verdict == verdict; }));
}

void checkComparisonOptions(const ComparisonOptions& options) {
  if (!(options.alpha > 0.0 && options.alpha < 1.0))
    throw Error("--alpha must be in (0, 1), got " + formatNumber(options.alpha, 6));
  if (!(options.minEffect >= 0.0)) throw Error("--min-effect must not be negative");
  if (!(options.tolerance >= 0.0)) throw Error("--tolerance must not be negative");
  if (!(options.solveTimeFloor >= 0.0)) throw Error("--solve-time-floor must not be negative");
  for (const auto& key : options.metrics) {
    try {
      trajectory::metricDescriptor(key);
    } catch (const Error&) {
      throw Error("--metrics: unknown metric '" + key + "' (metric keys: docs/metrics.md, e.g. execution_time_s)");
    }
  }
}

CampaignComparison compareCampaigns(const CampaignResults& base, const CampaignResults& current,
                                    const ComparisonOptions& options) {
  checkComparisonOptions(options);
  CampaignComparison comparison;
  comparison.base = base.source;
  comparison.current = current.source;
  comparison.options = options;

  std::set<std::string> problems;
  for (const auto& [problem, planners] : base.problems) problems.insert(problem);
  for (const auto& [problem, planners] : current.problems) problems.insert(problem);
  std::map<std::tuple<std::string, std::string, std::string>, std::vector<std::string>> settingDifferences;
  int matchedPairs = 0;
  for (const auto& problem : problems) {
    static const std::map<std::string, PlannerResults> none;
    const auto baseProblem = base.problems.find(problem), currentProblem = current.problems.find(problem);
    const auto& basePlanners = baseProblem == base.problems.end() ? none : baseProblem->second;
    const auto& currentPlanners = currentProblem == current.problems.end() ? none : currentProblem->second;
    std::set<std::string> planners;
    for (const auto& [planner, results] : basePlanners) planners.insert(planner);
    for (const auto& [planner, results] : currentPlanners) planners.insert(planner);
    for (const auto& planner : planners) {
      const auto b = basePlanners.find(planner), c = currentPlanners.find(planner);
      if (b == basePlanners.end() || c == currentPlanners.end()) {
        const bool inBase = b != basePlanners.end();
        (inBase ? comparison.onlyInBase : comparison.onlyInNew).push_back(pairName(problem, planner));
        auto row = newRow(problem, planner, "-");
        row.base = row.current = kNaN;
        (inBase ? row.baseCount : row.newCount) = (inBase ? b : c)->second.runs;
        row.note = inBase ? "only in base" : "only in new";
        comparison.rows.push_back(row);
        continue;
      }
      ++matchedPairs;
      addSettingDifferences(pairName(problem, planner), b->second, c->second, settingDifferences);
      comparison.rows.push_back(successRow(problem, planner, b->second, c->second));
      std::string pathNote;
      bool pathCompared = false;
      for (const auto& key : options.metrics) {
        auto row = metricRow(problem, planner, trajectory::metricDescriptor(key), b->second, c->second, options);
        const bool exactChange = row.method == ComparisonMethod::Exact && row.verdict != Verdict::Same;
        if (exactChange && !b->second.medianRun.empty() && !c->second.medianRun.empty()) {
          if (!pathCompared)
            pathNote = firstPathDifference(b->second.medianRun, c->second.medianRun, options.tolerance);
          pathCompared = true;
          row.note = pathNote;
        }
        comparison.rows.push_back(std::move(row));
      }
    }
  }

  for (auto& [key, pairs] : settingDifferences) {
    const auto& [setting, baseValue, currentValue] = key;
    if (static_cast<int>(pairs.size()) == matchedPairs) pairs.clear();  // every pair: say so once
    comparison.settings.push_back({setting, baseValue, currentValue, pairs});
  }

  std::vector<std::size_t> tested;
  std::vector<double> pValues;
  for (std::size_t i = 0; i < comparison.rows.size(); ++i) {
    const auto method = comparison.rows[i].method;
    if (method == ComparisonMethod::Fisher || method == ComparisonMethod::MannWhitney) {
      tested.push_back(i);
      pValues.push_back(comparison.rows[i].pValue);
    }
  }
  const auto adjusted = holmAdjusted(pValues);
  for (std::size_t k = 0; k < tested.size(); ++k) {
    auto& row = comparison.rows[tested[k]];
    row.adjustedPValue = adjusted[k];
    row.verdict = stochasticVerdict(row, options);
  }
  return comparison;
}

}  // namespace arcplan::benchmarks
