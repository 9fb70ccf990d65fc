#pragma once
// One scene query planned once and measured: what `arcplan plan` and the Python module's
// `arcplan.plan` both compute, so that they give the same numbers for the same inputs. The planner
// comes from the registry with its parameters; its path is simplified as simplifiesSolution says
// (solution_policy.h) and measured and judged by measureSolution as bench does (solution_measurement.h).
#include <cstdint>
#include <limits>
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
  // OMPL's seed is process-global: it is set before the problem exists (planning_problem.h). The
  // setup's samplers and simplifier and the arc planner's `seed` (unless given) follow it as a campaign
  // run with this run seed does (planners/seeded_sampling.h), so the same path comes out.
  std::optional<std::uint32_t> seed;
  std::optional<double> maxTcpSpeed;  // m/s: also time-scale the path (PCHIP) and measure the scaled metrics
  double clearance = 0.0;             // m every state and motion keeps (a suite's `clearance`); 0: no contact
};

enum class PlanStatus { Exact, Approximate, Failed };
// "exact", "approximate", "failed": the `status` of `plan --json`.
const char* toString(PlanStatus status);

// The JSON key (and Python attribute) of PlannedQuery::simplificationTime.
inline constexpr char kSimplificationTimeKey[] = "simplification_time_s";

struct PlannedQuery {
  PlanQueryOptions options;  // as asked, with the registered planner name
  std::string sceneName;
  std::string queryName;
  PlanStatus status = PlanStatus::Failed;
  std::string reason;      // why there is no exact path; empty for an exact one
  double solveTime = 0.0;  // s, the arc planner's own time or OMPL's planning time
  // s, OMPL's simplifier on a sampling planner's path (with the check that keeps it certified), or the arc
  // planner's simplification of its fallback's first plan (ArcPlannerResult::simplificationTime); 0 without one
  double simplificationTime = 0.0;
  std::map<std::string, std::string> parameterValues;  // every parameter of the planner after setting them
  std::optional<planners::ArcPlannerResult> arc;       // the arc planner's details
  trajectory::JointPath path;  // the (simplified) solution path, exact or approximate; empty without one
  std::optional<trajectory::PathMeasurement> measurement;  // when there is a path
  // With a path: its smallest (measured − required) clearance, as bench judges it (solution_measurement.h).
  double clearanceMargin = std::numeric_limits<double>::infinity();
  bool clearanceKept = true;  // MeasuredSolution::keptClearance(), the verdict JSON, Python and `plan` read

  // A path the arc planner's joint-space fallback found: why its line-and-arc search gave up and which of the
  // fallback's paths it kept (ArcPlannerResult::reason); nothing for any other path. `plan`, its JSON
  // (`fallback_reason`) and Python read it here.
  std::optional<std::string> fallbackReason() const;
};

// How the caller names the options in its messages: Python's keywords by default, the command line
// its options ("--time", "--vmax", "--clearance").
struct PlanOptionNames {
  std::string timeLimit = "plan: the time limit";
  std::string maxTcpSpeed = "plan: vmax";
  std::string clearance = "plan: the clearance";
};
// The one check of the options (planQuery calls it first): throws arcplan::Error "<name> must be ...".
void checkPlanQueryOptions(const PlanQueryOptions& options, const PlanOptionNames& names = {});

// Throws arcplan::Error for a bad option (non-positive or non-finite time limit or speed, a negative or
// non-finite clearance), an unknown
// planner or parameter, and as planners::makePlanningProblem does; a planner that finds no path is a
// result (status Failed with its reason), not an error.
PlannedQuery planQuery(std::shared_ptr<const collision::Scene> scene, const std::string& queryName,
                       const PlanQueryOptions& options);

// The result document of `plan --json` (docs/cli.md): scene, query, planner, status, solve time,
// time limit, parameters, seed, reason, the arc planner's details (a fallback's reason), waypoints, vmax, the metrics,
// the clearance asked for and whether the path kept it (clearance_m, clearance_kept).
nlohmann::json toJson(const PlannedQuery& planned);

}  // namespace arcplan::benchmarks
