// Campaign baselines for continuous integration (baseline.h).
#include "arcplan/benchmarks/baseline.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "arcplan/benchmarks/comparison_statistics.h"
#include "arcplan/benchmarks/ranking.h"
#include "arcplan/common/error.h"

namespace arcplan::benchmarks {
namespace {

const std::string kFormatName = "arcplan benchmark baseline";
constexpr int kQuantileCount = 21;  // 0 %, 5 %, ..., 100 %

nlohmann::json readJsonFile(const std::filesystem::path& file, const std::string& what) {
  std::ifstream in(file);
  if (!in) throw Error("cannot read " + what + " " + file.string());
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(file.string() + ": not valid JSON (" + e.what() + ")");
  }
}

nlohmann::json metricSummary(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  nlohmann::json summary{{"count", values.size()}};
  if (values.front() == values.back()) {
    summary["value"] = values.front();
    return summary;
  }
  std::vector<double> quantiles;
  for (int i = 0; i < kQuantileCount; ++i)
    quantiles.push_back(quantileOfSorted(values, i / double(kQuantileCount - 1)));
  summary["quantiles"] = quantiles;
  return summary;
}

// Field checks of a baseline file: each names the file and the field's path.
class BaselineReader {
public:
  explicit BaselineReader(std::filesystem::path file) : file_(std::move(file)) {}

  static std::string join(const std::string& field, const std::string& key) {
    return field.empty() ? key : field + "." + key;
  }
  [[noreturn]] void fail(const std::string& field, const std::string& expected) const {
    throw Error(file_.string() + ": " + field + ": expected " + expected +
                " (a file written by `arcplan bench baseline save`)");
  }
  const nlohmann::json& member(const nlohmann::json& object, const std::string& key, const std::string& field) const {
    if (!object.is_object() || !object.contains(key)) fail(join(field, key), "this field");
    return object.at(key);
  }
  std::string text(const nlohmann::json& object, const std::string& key, const std::string& field) const {
    const auto& value = member(object, key, field);
    if (!value.is_string()) fail(join(field, key), "a string");
    return value.get<std::string>();
  }
  long long count(const nlohmann::json& object, const std::string& key, const std::string& field, long long minimum,
                  long long maximum = kMaximumRuns) const {
    const auto& value = member(object, key, field);
    if (!value.is_number_integer() || value.get<long long>() < minimum || value.get<long long>() > maximum) {
      fail(join(field, key), "a whole number from " + std::to_string(minimum) + " to " + std::to_string(maximum));
    }
    return value.get<long long>();
  }
  double number(const nlohmann::json& object, const std::string& key, const std::string& field) const {
    const auto& value = member(object, key, field);
    if (!value.is_number() || !std::isfinite(value.get<double>())) fail(join(field, key), "a finite number");
    return value.get<double>();
  }
  const nlohmann::json& array(const nlohmann::json& object, const std::string& key, const std::string& field) const {
    const auto& value = member(object, key, field);
    if (!value.is_array()) fail(join(field, key), "an array");
    return value;
  }

  // `runs`: the result's runs; a summary of more values than runs is not one of this campaign.
  void checkMetric(const nlohmann::json& summary, const std::string& field, long long runs) const {
    count(summary, "count", field, 1, runs);
    const bool exact = summary.contains("value"), distribution = summary.contains("quantiles");
    if (exact == distribution) fail(field, "either \"value\" or \"quantiles\"");
    if (exact) {
      number(summary, "value", field);
      return;
    }
    const auto& quantiles = summary.at("quantiles");
    bool valid = quantiles.is_array() && quantiles.size() == kQuantileCount;
    for (std::size_t i = 0; valid && i < quantiles.size(); ++i) {
      valid = quantiles[i].is_number() && std::isfinite(quantiles[i].get<double>()) &&
              (i == 0 || quantiles[i].get<double>() >= quantiles[i - 1].get<double>());
    }
    if (!valid) fail(field + ".quantiles", std::to_string(kQuantileCount) + " finite numbers in increasing order");
  }

  void check(const nlohmann::json& baseline) const {
    if (!baseline.is_object() || !baseline.contains("format") || baseline["format"] != kFormatName) {
      fail("format", "\"" + kFormatName + "\"");
    }
    if (count(baseline, "version", "", 1) != kBaselineFormatVersion) {
      fail("version", std::to_string(kBaselineFormatVersion) + " (this arcplan's baseline format)");
    }
    const auto& campaign = member(baseline, "campaign", "");
    text(campaign, "suite", "campaign");
    count(campaign, "runs", "campaign", 1);
    number(campaign, "time_limit_s", "campaign");
    number(campaign, "vmax_mps", "campaign");
    if (campaign.contains("iteration_budget") && !campaign["iteration_budget"].is_null()) {
      count(campaign, "iteration_budget", "campaign", 1, kMaximumIterationBudget);
    }
    const auto& problems = array(campaign, "problems", "campaign");
    for (std::size_t i = 0; i < problems.size(); ++i) {
      if (!problems[i].is_string()) fail("campaign.problems[" + std::to_string(i) + "]", "a problem name");
    }
    const auto& planners = array(campaign, "planners", "campaign");
    for (std::size_t i = 0; i < planners.size(); ++i)
      text(planners[i], "name", "campaign.planners[" + std::to_string(i) + "]");
    const auto& results = array(baseline, "results", "");
    for (std::size_t i = 0; i < results.size(); ++i) {
      const std::string field = "results[" + std::to_string(i) + "]";
      text(results[i], "problem", field);
      text(results[i], "planner", field);
      const auto runs = count(results[i], "runs", field, 0);
      if (count(results[i], "successes", field, 0) > runs) fail(field + ".successes", "at most runs");
      const auto& settings = member(results[i], "settings", field);
      for (const auto& [name, value] : settings.items()) {
        if (!value.is_string()) fail(field + ".settings." + name, "a string");
      }
      const auto& metrics = member(results[i], "metrics", field);
      if (!metrics.is_object()) fail(field + ".metrics", "an object");
      for (const auto& [key, summary] : metrics.items()) checkMetric(summary, field + ".metrics." + key, runs);
    }
  }

private:
  std::filesystem::path file_;
};

// Values at the plotting positions (i - 0.5) / n of the distribution the quantiles describe.
std::vector<double> valuesFromQuantiles(const std::vector<double>& quantiles, std::size_t count) {
  std::vector<double> values;
  for (std::size_t i = 0; i < count; ++i) {
    values.push_back(quantileOfSorted(quantiles, (static_cast<double>(i) + 0.5) / static_cast<double>(count)));
  }
  return values;
}

}  // namespace

nlohmann::json makeBaseline(const std::filesystem::path& directory) {
  const auto manifestFile = directory / "campaign.json";
  if (!std::filesystem::is_regular_file(manifestFile)) {
    throw Error(directory.string() + ": not a campaign folder (no campaign.json)");
  }
  const auto manifest = readJsonFile(manifestFile, "campaign description");
  const auto results = loadCampaignResults(directory);  // requires benchmark.db: a finished campaign
  nlohmann::json entries = nlohmann::json::array();
  for (const auto& [problem, planners] : results.problems) {
    for (const auto& [planner, result] : planners) {
      nlohmann::json metrics = nlohmann::json::object();
      for (const auto& [key, values] : result.values) {
        if (!values.empty()) metrics[key] = metricSummary(values);
      }
      entries.push_back({{"problem", problem},
                         {"planner", planner},
                         {"runs", result.runs},
                         {"successes", result.successes},
                         {"settings", result.settings},
                         {"metrics", metrics}});
    }
  }
  nlohmann::json baseline{
      {"format", kFormatName}, {"version", kBaselineFormatVersion}, {"campaign", manifest}, {"results", entries}};
  BaselineReader(manifestFile).check(baseline);  // a campaign.json from elsewhere must not make an unreadable baseline
  return baseline;
}

nlohmann::json readBaseline(const std::filesystem::path& file) {
  const auto baseline = readJsonFile(file, "baseline file");
  BaselineReader(file).check(baseline);
  return baseline;
}

bool isBaselineFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  char first = 0;
  return static_cast<bool>(in >> first) && first == '{';
}

CampaignResults baselineResults(const nlohmann::json& baseline, const std::string& source) {
  CampaignResults results;
  results.source = source;
  for (const auto& entry : baseline.at("results")) {
    auto& result = results.problems[entry.at("problem").get<std::string>()][entry.at("planner").get<std::string>()];
    result.runs = entry.at("runs").get<int>();
    result.successes = entry.at("successes").get<int>();
    result.settings = entry.at("settings").get<std::map<std::string, std::string>>();
    for (const auto& [key, summary] : entry.at("metrics").items()) {
      const auto count = summary.at("count").get<std::size_t>();
      result.values[key] = summary.contains("value")
                               ? std::vector<double>(count, summary.at("value").get<double>())
                               : valuesFromQuantiles(summary.at("quantiles").get<std::vector<double>>(), count);
    }
  }
  return results;
}

Suite suiteForBaseline(const nlohmann::json& baseline, const std::optional<std::filesystem::path>& suiteFile) {
  const auto& campaign = baseline.at("campaign");
  const auto name = campaign.at("suite").get<std::string>();
  auto suite = loadSuite(suiteFile ? *suiteFile : findSuite(name));
  if (suite.name != name) {
    throw Error(suite.sourceFile.string() + ": suite '" + suite.name + "', but the baseline was made with suite '" +
                name + "'");
  }
  std::vector<std::string> labels;
  for (const auto& planner : campaign.at("planners")) labels.push_back(planner.at("name").get<std::string>());
  selectPlanners(suite, labels);
  std::vector<Problem> problems;
  for (const auto& problem : campaign.at("problems")) problems.push_back(suite.problem(problem.get<std::string>()));
  suite.problems = std::move(problems);
  std::vector<std::string> plots;
  for (const auto& plot : suite.plotProblems) {
    const bool kept =
        std::any_of(suite.problems.begin(), suite.problems.end(), [&](const Problem& p) { return p.name == plot; });
    if (kept) plots.push_back(plot);
  }
  suite.plotProblems = std::move(plots);
  suite.runs = campaign.at("runs").get<unsigned>();
  suite.timeLimit = campaign.at("time_limit_s").get<double>();
  suite.vMax = campaign.at("vmax_mps").get<double>();
  // Campaigns from before iteration budgets existed have none.
  const auto budget = campaign.value("iteration_budget", nlohmann::json(nullptr));
  suite.iterationBudget = budget.is_null() ? std::nullopt : std::optional<unsigned>(budget.get<unsigned>());
  return suite;
}

}  // namespace arcplan::benchmarks
