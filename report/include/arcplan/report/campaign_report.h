#pragma once
// The campaign report: the ranking (overall, by family, per problem) with every ranked metric and
// the success counts, the runs of every attribute for box plots, each plot problem's median-run
// speed profiles and TCP paths, the arm's link poses along each trajectory, the run settings and
// links back to the logs and the database.
#include <cstddef>
#include <filesystem>

#include <nlohmann/json.hpp>

namespace arcplan::report {

struct CampaignReportOptions {
  double animationRate = 25.0;       // Hz of the link-pose frames of the 3D view
  std::size_t profileSamples = 300;  // at most this many speed-profile / TCP-path samples per planner
};

// `input` is a campaign folder (with benchmark.db) or a benchmark database. `output` is where the
// HTML goes (links to logs and database are relative to it). What is missing (no arcplan columns,
// no path data, no joint columns) is listed under "missing" rather than failing. Throws
// arcplan::Error when the database cannot be read.
nlohmann::json campaignReportData(const std::filesystem::path& input, const std::filesystem::path& output,
                                  const CampaignReportOptions& options = {});

}  // namespace arcplan::report
