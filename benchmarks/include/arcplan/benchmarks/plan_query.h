#pragma once
// One scene query planned once and measured: what `arcplan plan` and the Python module's
// `arcplan.plan` both compute, so that they give the same numbers for the same inputs. The planner
// comes from the registry with its parameters; its path is simplified as simplifiesSolution says
// (solution_policy.h) and measured by trajectory::measurePath (time-scaled when a TCP speed limit is
// given, the obstacle clearance at every dense waypoint).
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "arcplan/collision/scene.h"
#include "arcplan/planners/arc_planner.h"
#include "arcplan/trajectory/joint_path.h"
#include "arcplan/trajectory/path_measurement.h"

namespace arcplan::benchmarks {

struct PlanQueryOptions {
  std::string planner = "arc";                                  // any spelling the registry accepts
  std::vector<std::pair<std::string, std::string>> parameters;  // (name, value) as `--param name=value`
  double timeLimit = 5.0;                                       // s
  // OMPL's seed is process-global: it is set before the problem exists (planning_problem.h).
  std::optional<std::uint32_t> seed;
  std::optional<double> maxTcpSpeed;  // m/s: also time-scale the path (PCHIP) and measure the scaled metrics
};

enum class PlanStatus { Exact, Approximate, Failed };
// "exact", "approximate", "failed": the `status` of `plan --json`.
const char* toString(PlanStatus status);

struct PlannedQuery {
  PlanQueryOptions options;  // as asked, with the registered planner name
  std::string sceneName;
  std::string queryName;
  PlanStatus status = PlanStatus::Failed;
  std::string reason;                                  // why there is no exact path; empty for an exact one
  double solveTime = 0.0;                              // s, the arc planner's own time or OMPL's planning time
  std::map<std::string, std::string> parameterValues;  // every parameter of the planner after setting them
  std::optional<planners::ArcPlannerResult> arc;       // the arc planner's details
  trajectory::JointPath path;  // the (simplified) solution path, exact or approximate; empty without one
  std::optional<trajectory::PathMeasurement> measurement;  // when there is a path
};

// Throws arcplan::Error for a bad option (non-positive or non-finite time limit or speed), an unknown
// planner or parameter, and as planners::makePlanningProblem does; a planner that finds no path is a
// result (status Failed with its reason), not an error.
PlannedQuery planQuery(std::shared_ptr<const collision::Scene> scene, const std::string& queryName,
                       const PlanQueryOptions& options);

// The result document of `plan --json` (docs/cli.md): scene, query, planner, status, solve time,
// time limit, parameters, seed, reason, the arc planner's details, waypoints, vmax and the metrics.
nlohmann::json toJson(const PlannedQuery& planned);

}  // namespace arcplan::benchmarks
