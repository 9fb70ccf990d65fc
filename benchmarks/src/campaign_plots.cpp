#include "campaign_plots.h"

#include <algorithm>

#include <unistd.h>

#include "arcplan/common/plotting.h"
#include "arcplan/common/text_formatting.h"
#include "campaign_layout.h"

namespace arcplan::benchmarks::detail {
namespace {

std::string fileSafe(const std::string& experiment) {
  std::string name = experiment;
  std::replace(name.begin(), name.end(), '/', '_');
  return name;
}

// Runs a plot script into a temporary PNG that replaces `target` only when the script succeeded.
void plot(const std::string& script, std::vector<std::string> arguments, const std::filesystem::path& target,
          std::vector<std::string>& notes) {
  auto temporary = target;
  temporary.replace_extension(".tmp" + std::to_string(::getpid()) + ".png");
  arguments.insert(arguments.end(), {"--out", temporary.string()});
  const auto outcome = runPlotScript(script, arguments);
  std::error_code ec;
  if (!outcome.ok) {
    std::filesystem::remove(temporary, ec);
    notes.push_back(target.filename().string() + ": " + outcome.message);
    return;
  }
  std::filesystem::rename(temporary, target, ec);
  if (ec) notes.push_back("cannot move " + temporary.string() + " to " + target.string() + ": " + ec.message());
}

// The box plots draw one panel per metric of the descriptor table, in its order.
std::vector<std::string> boxplotArguments(const std::filesystem::path& database, const std::string& order,
                                          const std::string& problem) {
  std::vector<std::string> arguments{"--db", database.string(), "--order", order};
  if (!problem.empty()) arguments.insert(arguments.end(), {"--problem", problem});
  for (const auto& metric : rankedMetrics()) {
    arguments.insert(arguments.end(), {"--metric", metric.label, joinText(metric.columns, ",")});
  }
  return arguments;
}

}  // namespace

void makePlots(const std::filesystem::path& database, const Ranking& ranking, const ReportOptions& options,
               std::vector<std::string>& notes) {
  if (!findMatplotlibPython()) {
    notes.push_back("plots skipped: no Python with matplotlib (install python3-matplotlib or set ARCPLAN_PYTHON)");
    return;
  }
  const auto directory = options.outDirectory / "plots";
  createDirectory(directory);
  std::vector<std::string> planners;
  for (const auto& standing : ranking.overall) planners.push_back(standing.planner);
  const std::string order = joinText(planners, ",");
  plot("plot_benchmark_boxplots.py", boxplotArguments(database, order, {}), directory / "boxplots_all.png", notes);
  for (const auto& problem : ranking.problems) {
    // Median-run data of this problem; merged shards each hold the planners they ran.
    std::vector<std::string> paths;
    for (const auto& root : options.pathDirectories) {
      const auto folder = (root / problem.problem).lexically_normal();
      if (std::filesystem::exists(folder / "scene.json") &&
          std::find(paths.begin(), paths.end(), folder.string()) == paths.end()) {
        paths.push_back(folder.string());
      }
    }
    // Per-problem figures for problems with plot data, and for every problem of small campaigns.
    if (paths.empty() && ranking.problemCount() > 4) continue;
    const auto name = fileSafe(problem.problem);
    plot("plot_benchmark_boxplots.py", boxplotArguments(database, order, problem.problem),
         directory / ("boxplots_" + name + ".png"), notes);
    if (paths.empty()) continue;
    std::vector<std::string> pathArguments{"--order", order, "--paths"};
    pathArguments.insert(pathArguments.end(), paths.begin(), paths.end());
    auto speed = pathArguments, view = pathArguments;
    speed.insert(speed.end(), {"--title", "TCP speed of each planner's median run — " + problem.problem});
    view.insert(view.end(), {"--title", "TCP paths of the median runs — " + problem.problem});
    plot("plot_benchmark_speed_profiles.py", speed, directory / ("speed_" + name + ".png"), notes);
    plot("plot_benchmark_paths3d.py", view, directory / ("paths3d_" + name + ".png"), notes);
  }
}

}  // namespace arcplan::benchmarks::detail
