#include "arcplan/benchmarks/plan_query.h"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <sstream>

#include "arcplan/benchmarks/solution_measurement.h"
#include "arcplan/benchmarks/solution_policy.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/joint_states.h"
#include "arcplan/common/error.h"
#include "arcplan/planners/certified_simplification.h"
#include "arcplan/planners/planner_registry.h"
#include "arcplan/planners/planning_problem.h"
#include "arcplan/planners/seeded_sampling.h"
#include "arcplan/trajectory/metric_descriptors.h"

namespace arcplan::benchmarks {
namespace {

// Why an OMPL planner ended without an exact path.
std::string omplReason(const ompl::base::PlannerStatus& status, const ompl::geometric::SimpleSetup& setup,
                       double time) {
  std::ostringstream reason;
  switch (ompl::base::PlannerStatus::StatusType(status)) {
    case ompl::base::PlannerStatus::APPROXIMATE_SOLUTION:
      reason << "no exact path within " << time << " s; the best path ends "
             << setup.getProblemDefinition()->getSolutionDifference() << " (joint-space distance) from the goal";
      break;
    case ompl::base::PlannerStatus::TIMEOUT:
      reason << "no path within the time limit of " << time << " s";
      break;
    case ompl::base::PlannerStatus::INVALID_START:
      reason << "invalid start state";
      break;
    case ompl::base::PlannerStatus::INVALID_GOAL:
      reason << "invalid goal state";
      break;
    default:
      reason << "planner status: " << status.asString();
  }
  return reason.str();
}

nlohmann::json arcDetails(const planners::ArcPlannerResult& result) {
  nlohmann::json detours = nlohmann::json::array();
  for (const planners::Detour& detour : result.detours) {
    detours.push_back({{"position_m", detour.position},
                       {"sagitta_m", detour.shape.sagitta},
                       {"half_chord_m", detour.shape.halfChord},
                       {"entry_radius_m", detour.shape.entryRadius},
                       {"exit_radius_m", detour.shape.exitRadius},
                       {"plane_angle_rad", detour.planeAngle}});
  }
  nlohmann::json vias = nlohmann::json::array();
  for (std::size_t i = 0; i < result.viaPoints.size(); ++i) {
    const Eigen::Vector3d& point = result.viaPoints[i];
    vias.push_back({{"position_m", {point.x(), point.y(), point.z()}}, {"blend_m", result.blends[i]}});
  }
  return {{"detours", detours},
          {"via_points", vias},
          {"obstacles", result.obstacles},
          {"analytic_tcp_path_length_m", result.tcpPathLength},
          {"routes_tried", result.routesTried}};
}

}  // namespace

void checkPlanQueryOptions(const PlanQueryOptions& options, const PlanOptionNames& names) {
  if (!(options.timeLimit > 0.0) || !std::isfinite(options.timeLimit))
    throw Error(names.timeLimit + " must be a positive number of seconds");
  if (options.maxTcpSpeed && (!(*options.maxTcpSpeed > 0.0) || !std::isfinite(*options.maxTcpSpeed)))
    throw Error(names.maxTcpSpeed + " must be a positive TCP speed in m/s");
  if (!(options.clearance >= 0.0) || !std::isfinite(options.clearance))
    throw Error(names.clearance + " must be a distance >= 0 m");
}

const char* toString(PlanStatus status) {
  switch (status) {
    case PlanStatus::Exact:
      return "exact";
    case PlanStatus::Approximate:
      return "approximate";
    case PlanStatus::Failed:
      break;
  }
  return "failed";
}

PlannedQuery planQuery(std::shared_ptr<const collision::Scene> scene, const std::string& queryName,
                       const PlanQueryOptions& options) {
  checkPlanQueryOptions(options);
  // OMPL's seed must be set before anything random exists. Set again in a process that has planned
  // before (Python), OMPL re-seeds its seed generator, so every RNG made from here on draws the same
  // as in a fresh process, but logs an error saying it would not be deterministic: kept quiet.
  if (options.seed) {
    // OMPL's seed and log level are process-wide: two plans seeding at once (Python threads) must not
    // interleave here, or one restores the other's LOG_NONE for good.
    static std::mutex seeding;
    const std::lock_guard<std::mutex> lock(seeding);
    const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    ompl::RNG::setSeed(*options.seed);
    ompl::msg::setLogLevel(level);
  }
  PlannedQuery planned;
  planned.options = options;
  planned.options.planner = planners::canonicalPlannerName(options.planner);
  const std::string& plannerName = planned.options.planner;
  planned.sceneName = scene->name;

  planners::PlanningProblemOptions problemOptions;
  problemOptions.clearance = options.clearance;
  planners::PlanningProblem problem = planners::makePlanningProblem(std::move(scene), queryName, problemOptions);
  planned.queryName = problem.queryName;
  ompl::geometric::SimpleSetup& setup = *problem.setup;
  const ompl::base::PlannerPtr planner =
      planners::makePlanner(plannerName, setup.getSpaceInformation(), problem.plannerContext(), options.parameters);
  // A clearance asked for is the arc planner's too, as in a campaign with that clearance (without one it keeps its
  // own).
  if (options.clearance > 0.0) {
    const bool given = std::any_of(options.parameters.begin(), options.parameters.end(),
                                   [](const auto& parameter) { return parameter.first == "clearance"; });
    keepProblemClearance(*planner, options.clearance, given);
  }
  setup.setPlanner(planner);
  setup.setup();
  if (options.seed) {
    // What a campaign run with run seed S draws (job_runner.cpp): samplers and simplifier seeded from S,
    // and the arc planner's `seed` S unless given, so `plan --seed S` repeats that run's path.
    const bool seedGiven = std::any_of(options.parameters.begin(), options.parameters.end(),
                                       [](const auto& parameter) { return parameter.first == "seed"; });
    planners::seedRun(setup, *planner, *options.seed, seedGiven);
  }
  // The deadline read by the planner itself: SimpleSetup::solve(t) from 1 s on evaluates it on a thread that sleeps in
  // 1 ms steps and is joined after the solve, up to ~1 ms more per plan (planner_registry.h, lastSolveTime).
  const ompl::base::PlannerStatus status = setup.solve(ompl::base::timedPlannerTerminationCondition(options.timeLimit));
  const bool haveExact = setup.haveExactSolutionPath();
  const bool havePath = setup.haveSolutionPath();
  const auto* arc = dynamic_cast<const planners::ArcPlanner*>(planner.get());

  // The arc path is already the TCP path; sampling planners' paths get OMPL's shortcutting, kept only
  // where the motion validator accepts every motion of the result (certified_simplification.h).
  if (havePath && simplifiesSolution(plannerName)) {
    const auto simplifying = std::chrono::steady_clock::now();
    planners::simplifySolutionKeepingCertified(setup);
    planned.simplificationTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - simplifying).count();
  }

  planned.status = haveExact                                                   ? PlanStatus::Exact
                   : status == ompl::base::PlannerStatus::APPROXIMATE_SOLUTION ? PlanStatus::Approximate
                                                                               : PlanStatus::Failed;
  planned.solveTime = planners::lastSolveTime(*planner);
  if (arc) planned.simplificationTime = arc->lastResult().simplificationTime;
  planner->params().getParams(planned.parameterValues);
  if (!haveExact) planned.reason = arc ? arc->lastResult().reason : omplReason(status, setup, options.timeLimit);
  if (arc) planned.arc = arc->lastResult();
  if (havePath) {
    planned.path = collision::waypointsOf(setup.getSolutionPath());
    std::optional<trajectory::TimeScalingOptions> scaling;
    if (options.maxTcpSpeed) {
      scaling.emplace();
      scaling->maxTcpSpeed = *options.maxTcpSpeed;
    }
    MeasuredSolution measured = measureSolution(problem, planned.path, scaling);
    planned.measurement = std::move(measured.measurement);
    planned.clearanceMargin = measured.clearanceMargin;
    planned.clearanceKept = measured.keptClearance();
  }
  return planned;
}

std::optional<std::string> PlannedQuery::fallbackReason() const {
  if (!arc || path.empty() || arc->kind != planners::ArcPlannerResult::Kind::Fallback) return std::nullopt;
  return arc->reason;
}

nlohmann::json toJson(const PlannedQuery& planned) {
  nlohmann::json document = {{"scene", planned.sceneName},
                             {"query", planned.queryName},
                             {"planner", planned.options.planner},
                             {"status", toString(planned.status)},
                             {trajectory::solveTimeDescriptor().key, planned.solveTime},
                             {kSimplificationTimeKey, planned.simplificationTime},
                             {"time_limit_s", planned.options.timeLimit},
                             {"parameters", planned.parameterValues}};
  if (planned.options.seed) document["seed"] = *planned.options.seed;
  if (!planned.reason.empty()) document["reason"] = planned.reason;
  if (planned.arc) {
    document["arc"] = arcDetails(*planned.arc);
    if (!planned.path.empty()) {
      document["mode"] = planned.arc->mode();
      document["cartesian_fraction"] = planned.arc->cartesianFraction;
      if (const auto why = planned.fallbackReason()) document["fallback_reason"] = *why;
    }
  }
  if (planned.measurement) {
    document["waypoints"] = planned.path.size();
    if (planned.options.maxTcpSpeed) document["vmax_mps"] = *planned.options.maxTcpSpeed;
    document.update(trajectory::toJson(*planned.measurement));
    document["clearance_m"] = planned.options.clearance;
    document["clearance_kept"] = planned.clearanceKept;
  }
  return document;
}

}  // namespace arcplan::benchmarks
