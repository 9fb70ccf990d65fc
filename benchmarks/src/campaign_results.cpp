// Reading a campaign's results for `bench compare` and baselines (campaign_results.h).
#include "arcplan/benchmarks/campaign_results.h"

#include "arcplan/benchmarks/baseline.h"
#include "arcplan/benchmarks/benchmark_database.h"
#include "arcplan/common/error.h"

namespace arcplan::benchmarks {

CampaignResults campaignResultsFromRuns(const std::string& source, const CampaignRuns& runs,
                                        const PerPair<PairSettings>& settings) {
  CampaignResults results;
  results.source = source;
  for (const auto& [problem, planners] : runs) {
    for (const auto& [planner, plannerRuns] : planners) {
      auto& entry = results.problems[problem][planner];
      for (const auto& run : plannerRuns) {
        ++entry.runs;
        if (!run.succeeded()) continue;
        ++entry.successes;
        for (const auto& [key, value] : run.values) {
          if (run.value(key)) entry.values[key].push_back(value);
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
    const auto recorded = readBenchmarkDatabase(campaignDatabase(input));
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
  const auto recorded = readBenchmarkDatabase(input);
  return campaignResultsFromRuns(input.string(), recorded.runs, recorded.settings);
}

}  // namespace arcplan::benchmarks
