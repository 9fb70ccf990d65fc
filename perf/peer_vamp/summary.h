#pragma once
// What the side-by-side benchmark reports (perf/peer_vamp_mbm.cpp): one Outcome per planner and
// problem, summarised per planner and per family as JSON and as Markdown tables.
#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "vamp_side.h"

namespace arcplan::peer_vamp {

struct Outcome {
  std::string family, problem;
  bool inputsValid = false;  // start and goal valid under the planner's own collision model
  bool solved = false;
  std::string reason;  // why not solved
  double totalUs = 0.0, planningUs = 0.0, simplificationUs = 0.0;
  std::optional<double> wallUs;  // VAMP: steady_clock around its calls (its totalUs is its own timer)
  double pathCost = 0.0;         // joint-space length [rad]
  std::size_t waypoints = 0;
  std::string mode;  // arc planner
  // The exact check of the path (solved problems only).
  bool validExact = false;
  std::string exactFailure;
  double certificationUs = 0.0;  // µs to certify the path under the exact meshes (valid paths; PathCheck)
  double startError = 0.0, goalError = 0.0;
  Joints pathStart{}, pathEnd{};
};

// Linear interpolation between order statistics (numpy's and pandas' default), p in [0, 1]; nullopt
// for no values.
std::optional<double> percentile(std::vector<double> values, double p);

// problems, valid_inputs, solved, total_us_median, total_us_p95, planning/simplification medians,
// paths_valid_exact, path_cost_rad_median (times and costs over solved problems), certification_us_median and _p95
// (over the paths valid under the exact meshes); `families` with
// the same per family and `per_problem` with every outcome.
nlohmann::json plannerJson(const std::vector<Outcome>& outcomes);

// Markdown: one table over all problems and one per family; a row per planner.
std::string markdownTables(const std::map<std::string, std::vector<Outcome>>& byPlanner,
                           const std::vector<std::string>& plannerOrder);

}  // namespace arcplan::peer_vamp
