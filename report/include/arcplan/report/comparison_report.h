#pragma once
// The comparison page of `arcplan bench compare --html` (and `bench baseline check --html`): the
// verdict counts, the pairs on one side only, the differing settings, the verdict table (sortable)
// and, per problem, side-by-side box plots of every compared metric, base next to new for each
// planner. One self-contained HTML file like the other reports (html_page.h).
#include <filesystem>

#include <nlohmann/json.hpp>

#include "arcplan/benchmarks/campaign_comparison.h"

namespace arcplan::report {

// What the page's script reads: {comparison: comparisonJson(...), metrics: [{key, label,
// lower_is_better}], values: {problem: {planner: {base|new: {runs, successes, <metric key>: [values
// of the successful runs]}}}}, missing: [...]}.
nlohmann::json comparisonReportData(const benchmarks::CampaignComparison& comparison,
                                    const benchmarks::CampaignResults& base,
                                    const benchmarks::CampaignResults& current);

// Writes the page atomically. Throws arcplan::Error before writing when plotly.js or a page file is missing.
void writeComparisonReport(const std::filesystem::path& file, const benchmarks::CampaignComparison& comparison,
                           const benchmarks::CampaignResults& base, const benchmarks::CampaignResults& current);

}  // namespace arcplan::report
