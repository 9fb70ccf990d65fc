#pragma once
// The campaign's figures, drawn by the matplotlib scripts in scripts/plot/ from benchmark.db and the
// median-run files: box plots of every metric (all problems, and per problem), the TCP speed
// profiles and the 3D TCP paths of the median runs. Plots are an extra of a campaign: one that
// cannot be drawn becomes a note, never a failed campaign. Internal to arcplan::benchmarks.
#include <filesystem>
#include <string>
#include <vector>

#include "arcplan/benchmarks/campaign.h"

namespace arcplan::benchmarks::detail {

void makePlots(const std::filesystem::path& database, const Ranking& ranking, const ReportOptions& options,
               std::vector<std::string>& notes);

}  // namespace arcplan::benchmarks::detail
