#pragma once
// Where a campaign keeps what in its output directory (the layout is in campaign.h), and the files
// that describe the campaign itself: campaign.json (its settings) and the plot scenes. The lock on the
// directory is in campaign_lock.h. Internal to arcplan::benchmarks.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "arcplan/benchmarks/campaign.h"
#include "job_runner.h"

namespace arcplan::benchmarks::detail {

// Throws arcplan::Error naming the directory when it cannot be created.
void createDirectory(const std::filesystem::path& directory);

// Writes campaign.json, or checks that the existing one has the suite's settings: a resumed or
// sharded campaign must run exactly the settings its directory was started with, since one ranking
// of runs with different settings would compare incomparable runs. Throws arcplan::Error otherwise.
void claimOutputDirectory(const std::filesystem::path& directory, const Suite& suite);

// Why the job's existing log does not count as done (benchmarkLogProblem with the job's experiment,
// planner and run count), or nullopt when it is complete.
std::optional<std::string> jobLogProblem(const std::filesystem::path& out, const Suite& suite, const Job& job);

std::string jobLabel(const Suite& suite, const Job& job);  // "<problem> · <planner>"
JobFiles jobFiles(const std::filesystem::path& out, const Suite& suite, const Job& job);

// Problems listed under the suite's `plots` get median-run files and a scene.json for the plots.
bool isPlotProblem(const Suite& suite, const Problem& problem);
std::filesystem::path pathsDirectory(const std::filesystem::path& out, const Suite& suite, const Problem& problem);
// What the 3D plot needs besides the paths: obstacles and the TCP positions of start and goal.
void writePlotScene(const std::filesystem::path& file, const Problem& problem, double vMax);

}  // namespace arcplan::benchmarks::detail
