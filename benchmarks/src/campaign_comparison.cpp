// bench compare: matching two campaigns' runs, the verdict of every (pair, metric) row, and the
// comparison tables (campaign_comparison.h).
#include "arcplan/benchmarks/campaign_comparison.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <tuple>

#include "arcplan/benchmarks/baseline.h"
#include "arcplan/benchmarks/comparison_statistics.h"
#include "arcplan/benchmarks/ranking.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/common/text_parsing.h"
#include "arcplan/trajectory/metric_descriptors.h"

namespace arcplan::benchmarks {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const std::string kSolveTimeKey = "solve_time_s";

std::string pairName(const std::string& problem, const std::string& planner) { return problem + " · " + planner; }

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

// ---- median-run files: the first waypoint where two deterministic paths part -------------------

struct PathTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

PathTable readPathTable(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw Error("cannot read median-run file " + file.string());
  PathTable table;
  std::string line;
  int lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (line.empty() || line.front() == '#') continue;
    const auto fields = splitFields(line, ',');
    if (table.columns.empty()) {
      for (const auto field : fields) table.columns.emplace_back(trim(field));
      continue;
    }
    std::vector<double> row;
    for (const auto field : fields) {
      const auto value = parseDouble(field);
      if (!value)
        throw Error(file.string() + ":" + std::to_string(lineNumber) + ": expected numbers, got '" + line + "'");
      row.push_back(*value);
    }
    if (row.size() != table.columns.size()) {
      throw Error(file.string() + ":" + std::to_string(lineNumber) + ": expected " +
                  std::to_string(table.columns.size()) + " values as in the header");
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

// "" when the paths agree within the tolerance; else where they first differ.
std::string firstPathDifference(const std::filesystem::path& baseFile, const std::filesystem::path& currentFile,
                                double tolerance) {
  const auto base = readPathTable(baseFile), current = readPathTable(currentFile);
  std::vector<std::pair<std::size_t, std::size_t>> shared;  // column index in base, in current
  for (std::size_t i = 0; i < base.columns.size(); ++i) {
    const auto found = std::find(current.columns.begin(), current.columns.end(), base.columns[i]);
    if (found != current.columns.end())
      shared.emplace_back(i, static_cast<std::size_t>(found - current.columns.begin()));
  }
  // Where the paths part geometrically says more than where their timing does: positions first.
  const auto timing = [&](const std::pair<std::size_t, std::size_t>& columns) {
    return base.columns[columns.first] == "t" || base.columns[columns.first] == "tcp_speed";
  };
  const std::size_t rows = std::min(base.rows.size(), current.rows.size());
  for (const bool timingColumns : {false, true}) {
    for (std::size_t r = 0; r < rows; ++r) {
      for (const auto& columns : shared) {
        const auto [b, c] = columns;
        if (timing(columns) != timingColumns || std::abs(base.rows[r][b] - current.rows[r][c]) <= tolerance) continue;
        return "median runs first differ at waypoint " + std::to_string(r) + ": " + base.columns[b] + " " +
               formatNumber(base.rows[r][b], 9) + " -> " + formatNumber(current.rows[r][c], 9);
      }
    }
  }
  if (base.rows.size() != current.rows.size()) {
    return "median runs agree on their first " + std::to_string(rows) + " waypoints, then have " +
           std::to_string(base.rows.size()) + " -> " + std::to_string(current.rows.size()) + " waypoints";
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
  if (row.metric == kSolveTimeKey && std::abs(row.current - row.base) < options.solveTimeFloor) return Verdict::Same;
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

// ---- formatting --------------------------------------------------------------------------------

std::string number(double value) { return std::isnan(value) ? "-" : formatNumber(value, 7); }

std::string effectText(const ComparisonRow& row) {
  if (row.method == ComparisonMethod::None) return "-";
  if (row.metric == kSuccessRateKey) return (row.effect >= 0 ? "+" : "") + formatNumber(100.0 * row.effect, 3) + " pp";
  return (row.effect >= 0 ? "+" : "") + formatNumber(100.0 * row.effect, 3) + " %";
}

std::string pText(double p) { return std::isnan(p) ? "-" : formatNumber(p, 3); }

std::string valueText(const ComparisonRow& row, double value) {
  if (row.metric == kSuccessRateKey && !std::isnan(value)) return formatNumber(100.0 * value, 4) + " %";
  return number(value);
}

std::string metricLabel(const std::string& key) {
  if (key == kSuccessRateKey) return "success rate";
  if (key == "-") return "-";
  return trajectory::metricDescriptor(key).label;
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

nlohmann::json jsonNumber(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

const std::vector<std::string>& defaultComparedMetrics() {
  static const std::vector<std::string> keys{"execution_time_s", "tcp_path_length_m", "solve_time_s", "min_clearance_m",
                                             "peak_tcp_speed_mps"};
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

CampaignResults campaignResultsFromRuns(
    const std::string& source,
    const std::map<std::string, std::map<std::string, std::vector<std::map<std::string, double>>>>& runs,
    const std::map<std::string, std::map<std::string, std::map<std::string, std::string>>>& settings) {
  CampaignResults results;
  results.source = source;
  for (const auto& [problem, planners] : runs) {
    for (const auto& [planner, plannerRuns] : planners) {
      auto& entry = results.problems[problem][planner];
      for (const auto& run : plannerRuns) {
        ++entry.runs;
        const auto time = run.find("execution_time_s");
        if (time == run.end() || !std::isfinite(time->second)) continue;  // a failed run (rankRuns' rule)
        ++entry.successes;
        for (const auto& [key, value] : run) {
          if (std::isfinite(value)) entry.values[key].push_back(value);
        }
      }
      const auto problemSettings = settings.find(problem);
      if (problemSettings == settings.end()) continue;
      const auto plannerSettings = problemSettings->second.find(planner);
      if (plannerSettings != problemSettings->second.end()) entry.settings = plannerSettings->second;
    }
  }
  return results;
}

CampaignResults loadCampaignResults(const std::filesystem::path& input) {
  if (std::filesystem::is_directory(input)) {
    const auto database = input / "benchmark.db";
    if (!std::filesystem::is_regular_file(database)) {
      throw Error(input.string() +
                  ": not a finished campaign folder (no benchmark.db; `arcplan bench` writes it once "
                  "every job of the campaign is done)");
    }
    const auto recorded = readRecordedRuns(database);
    auto results = campaignResultsFromRuns(input.string(), recorded.runs, recorded.settings);
    for (auto& [problem, planners] : results.problems) {
      for (auto& [planner, entry] : planners) {
        const auto medianRun = input / "paths" / problem / (planner + ".csv");
        if (std::filesystem::is_regular_file(medianRun)) entry.medianRun = medianRun;
      }
    }
    return results;
  }
  if (!std::filesystem::exists(input))
    throw Error(input.string() + ": no such campaign folder, database or baseline file");
  if (isBaselineFile(input)) return baselineResults(readBaseline(input), input.string());
  const auto recorded = readRecordedRuns(input);
  return campaignResultsFromRuns(input.string(), recorded.runs, recorded.settings);
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

std::string comparisonMarkdown(const CampaignComparison& comparison, bool onlyChanges) {
  std::ostringstream out;
  const auto& o = comparison.options;
  out << "# Campaign comparison\n\n"
      << "- base: `" << comparison.base << "`\n- new: `" << comparison.current << "`\n"
      << "- verdicts: " << comparison.count(Verdict::Worse) << " worse, " << comparison.count(Verdict::Better)
      << " better, " << comparison.count(Verdict::Same) << " same, " << comparison.count(Verdict::NotComparable)
      << " not comparable\n"
      << "- thresholds: alpha " << formatNumber(o.alpha, 3) << " (Holm over the stochastic rows), minimum effect "
      << formatNumber(100.0 * o.minEffect, 3) << " %, exact tolerance " << formatNumber(o.tolerance, 3)
      << ", solve-time floor " << formatNumber(o.solveTimeFloor, 3) << " s\n";

  if (!comparison.onlyInBase.empty() || !comparison.onlyInNew.empty()) {
    out << "\n## On one side only\n\n";
    for (const auto& pair : comparison.onlyInBase) out << "- only in base: " << pair << "\n";
    for (const auto& pair : comparison.onlyInNew) out << "- only in new: " << pair << "\n";
  }
  if (!comparison.settings.empty()) {
    out << "\n## Different settings\n\n| setting | base | new | where |\n|---|---|---|---|\n";
    for (const auto& difference : comparison.settings) {
      out << "| " << difference.setting << " | " << difference.base << " | " << difference.current << " | "
          << (difference.pairs.empty() ? std::string("every pair") : joinText(difference.pairs, ", ")) << " |\n";
    }
  }
  out << "\n## Results\n\n";
  int hidden = 0;
  std::ostringstream table;
  for (const auto& row : comparison.rows) {
    if (onlyChanges && row.verdict == Verdict::Same) {
      ++hidden;
      continue;
    }
    table << "| " << row.problem << " | " << row.planner << " | " << metricLabel(row.metric) << " | " << row.baseCount
          << " → " << row.newCount << " | " << valueText(row, row.base) << " | " << valueText(row, row.current) << " | "
          << effectText(row) << " | " << methodName(row.method) << " | " << pText(row.pValue) << " | "
          << pText(row.adjustedPValue) << " | **" << verdictName(row.verdict) << "** | " << row.note << " |\n";
  }
  if (hidden < static_cast<int>(comparison.rows.size())) {
    out << "Values: success rate, the exact value, or the median of the successful runs; n: runs (success rate) or "
           "successful runs (metrics).\n\n"
        << "| problem | planner | metric | n | base | new | effect | test | p | p (Holm) | verdict | note |\n"
        << "|---|---|---|---:|---:|---:|---:|---|---:|---:|---|---|\n"
        << table.str();
  }
  if (hidden > 0) out << "\n" << hidden << " row(s) with verdict \"same\" not shown.\n";
  return out.str();
}

nlohmann::json comparisonJson(const CampaignComparison& comparison) {
  const auto& o = comparison.options;
  nlohmann::json settings = nlohmann::json::array();
  for (const auto& difference : comparison.settings) {
    settings.push_back(
        {{"setting", difference.setting},
         {"base", difference.base},
         {"new", difference.current},
         {"pairs", difference.pairs.empty() ? nlohmann::json("all") : nlohmann::json(difference.pairs)}});
  }
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& row : comparison.rows) {
    rows.push_back({{"problem", row.problem},
                    {"planner", row.planner},
                    {"metric", row.metric},
                    {"test", methodName(row.method)},
                    {"base_n", row.baseCount},
                    {"new_n", row.newCount},
                    {"base", jsonNumber(row.base)},
                    {"new", jsonNumber(row.current)},
                    {"effect", row.method == ComparisonMethod::None ? nlohmann::json(nullptr) : jsonNumber(row.effect)},
                    {"p", jsonNumber(row.pValue)},
                    {"p_holm", jsonNumber(row.adjustedPValue)},
                    {"rank_biserial", jsonNumber(row.rankBiserial)},
                    {"verdict", verdictName(row.verdict)},
                    {"note", row.note}});
  }
  return {{"base", comparison.base},
          {"new", comparison.current},
          {"options",
           {{"alpha", o.alpha},
            {"min_effect", o.minEffect},
            {"tolerance", o.tolerance},
            {"solve_time_floor_s", o.solveTimeFloor},
            {"metrics", o.metrics}}},
          {"counts",
           {{"worse", comparison.count(Verdict::Worse)},
            {"better", comparison.count(Verdict::Better)},
            {"same", comparison.count(Verdict::Same)},
            {"not_comparable", comparison.count(Verdict::NotComparable)}}},
          {"only_in_base", comparison.onlyInBase},
          {"only_in_new", comparison.onlyInNew},
          {"settings", settings},
          {"rows", rows}};
}

std::string comparisonCsv(const CampaignComparison& comparison) {
  std::ostringstream out;
  out << "problem,planner,metric,test,base_n,new_n,base,new,effect,p,p_holm,verdict,note\n";
  const auto csvNumber = [](double value) { return std::isnan(value) ? std::string() : formatNumber(value, 10); };
  for (const auto& row : comparison.rows) {
    out << csvField(row.problem) << "," << csvField(row.planner) << "," << row.metric << "," << methodName(row.method)
        << "," << row.baseCount << "," << row.newCount << "," << csvNumber(row.base) << "," << csvNumber(row.current)
        << "," << (row.method == ComparisonMethod::None ? std::string() : csvNumber(row.effect)) << ","
        << csvNumber(row.pValue) << "," << csvNumber(row.adjustedPValue) << "," << verdictName(row.verdict) << ","
        << csvField(row.note) << "\n";
  }
  return out.str();
}

void writeComparison(const CampaignComparison& comparison, const std::filesystem::path& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw Error("cannot create directory " + directory.string() + ": " + ec.message());
  writeFileAtomically(directory / "comparison.md", comparisonMarkdown(comparison));
  writeFileAtomically(directory / "comparison.json", comparisonJson(comparison).dump(2) + "\n");
  writeFileAtomically(directory / "comparison.csv", comparisonCsv(comparison));
}

}  // namespace arcplan::benchmarks
