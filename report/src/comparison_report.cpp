#include "arcplan/report/comparison_report.h"

#include "arcplan/report/html_page.h"
#include "arcplan/report/web_assets.h"
#include "arcplan/trajectory/metric_descriptors.h"

namespace arcplan::report {
namespace {

nlohmann::json sideValues(const benchmarks::PlannerResults& results, const std::vector<std::string>& metrics) {
  nlohmann::json side{{"runs", results.runs}, {"successes", results.successes}};
  for (const auto& key : metrics) {
    const auto found = results.values.find(key);
    side[key] = found == results.values.end() ? std::vector<double>{} : found->second;
  }
  return side;
}

}  // namespace

nlohmann::json comparisonReportData(const benchmarks::CampaignComparison& comparison,
                                    const benchmarks::CampaignResults& base,
                                    const benchmarks::CampaignResults& current) {
  const auto& keys = comparison.options.metrics;
  nlohmann::json metrics = nlohmann::json::array();
  for (const auto& key : keys) {
    const auto& descriptor = trajectory::metricDescriptor(key);
    metrics.push_back({{"key", key}, {"label", descriptor.label}, {"lower_is_better", descriptor.lowerIsBetter}});
  }
  nlohmann::json values = nlohmann::json::object();
  for (const auto& [label, side] :
       {std::pair<const char*, const benchmarks::CampaignResults*>{"base", &base}, {"new", &current}}) {
    for (const auto& [problem, planners] : side->problems) {
      for (const auto& [planner, results] : planners) values[problem][planner][label] = sideValues(results, keys);
    }
  }
  nlohmann::json missing = nlohmann::json::array();
  if (!comparison.onlyInBase.empty() || !comparison.onlyInNew.empty()) {
    missing.push_back("Pairs on one side only have no side-by-side box: they are listed under Verdicts.");
  }
  return {{"comparison", benchmarks::comparisonJson(comparison)},
          {"metrics", metrics},
          {"values", values},
          {"missing", missing}};
}

void writeComparisonReport(const std::filesystem::path& file, const benchmarks::CampaignComparison& comparison,
                           const benchmarks::CampaignResults& base, const benchmarks::CampaignResults& current) {
  const auto assets = loadWebAssets(ReportKind::Comparison);
  const auto name = [](const std::string& source) {
    const auto path = std::filesystem::path(source).lexically_normal();
    return path.filename().empty() ? path.parent_path().filename().string() : path.filename().string();
  };
  writeHtmlPage(file, assets,
                "arcplan campaign comparison — " + name(comparison.base) + " vs " + name(comparison.current),
                comparisonReportData(comparison, base, current));
}

}  // namespace arcplan::report
