// bench compare's tables: comparison.md, comparison.json and comparison.csv (campaign_comparison.h).
#include <cmath>
#include <sstream>

#include "arcplan/benchmarks/campaign_comparison.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/trajectory/metric_descriptors.h"

namespace arcplan::benchmarks {
namespace {

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
