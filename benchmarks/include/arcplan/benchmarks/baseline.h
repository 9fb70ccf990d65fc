#pragma once
// A campaign baseline for continuous integration (`arcplan bench baseline save|check`): one small
// JSON file the user commits, holding the campaign's settings (its campaign.json) and per (problem,
// planner) the run and success counts, the settings the logs recorded, and per metric either the
// exact value (when every successful run gave the same, as the arc planner does) or, for stochastic
// planners, the distribution as 21 quantiles (0 %, 5 %, ..., 100 %). `check` runs the campaign the
// baseline describes again and compares the new runs with it (campaign_comparison.h).
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "arcplan/benchmarks/campaign_comparison.h"
#include "arcplan/benchmarks/suite.h"

namespace arcplan::benchmarks {

inline constexpr int kBaselineFormatVersion = 1;

// The baseline of a finished campaign folder (campaign.json + benchmark.db). Throws arcplan::Error
// when the folder is not a finished campaign.
nlohmann::json makeBaseline(const std::filesystem::path& campaignDirectory);

// Reads and checks a baseline file; throws arcplan::Error naming the file and the field otherwise.
nlohmann::json readBaseline(const std::filesystem::path& file);

// True when the file looks like a baseline (a JSON object with the baseline's format key), so
// `bench compare` can take one in place of a campaign.
bool isBaselineFile(const std::filesystem::path& file);

// The results a baseline describes, as a campaign's: exact values repeated `count` times; a
// distribution as `count` values at the plotting positions (i - 0.5) / count of its quantiles, so
// the rank test sees the baseline's distribution at the 5 % resolution it was saved with.
CampaignResults baselineResults(const nlohmann::json& baseline, const std::string& source);

// The suite to run again for `check`: the baseline's suite (by its recorded name, or `suiteFile`
// when given) restricted to the baseline's planners and problems, with its runs, time limit, TCP
// speed limit and iteration budget. Throws arcplan::Error when the suite lacks one of the baseline's problems.
Suite suiteForBaseline(const nlohmann::json& baseline, const std::optional<std::filesystem::path>& suiteFile);

}  // namespace arcplan::benchmarks
