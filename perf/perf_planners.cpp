// Planner solve times on the thesis query (thesis_obstacle.yaml, A_to_B; the certified motion
// validator): the arc planner with the thesis shape h = 0.5 r (defaults: waypoints 1 cm apart, every
// motion validated; and variants), its auto mode (via-point search), the straight line of
// thesis_free, and RRTConnect on the same problem.
// Each benchmark times every solve itself and reports the median (counter `median_us`), because a
// sampling planner's mean is dominated by its rare long runs. ArcVsRRTConnect alternates the two
// planners in one loop and reports the ratio of their medians (`speedup`).
// Run: build/perf/arcplan_perf --benchmark_filter=Planner
#include <benchmark/benchmark.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <vector>

#include "arcplan/common/resources.h"
#include "arcplan/planners/planner_registry.h"
#include "arcplan/planners/planning_problem.h"

namespace {

using arcplan::planners::PlanningProblem;
using Parameters = std::vector<std::pair<std::string, std::string>>;

PlanningProblem& problem(const std::string& sceneName) {
  static std::map<std::string, PlanningProblem> problems;
  auto found = problems.find(sceneName);
  if (found == problems.end()) {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    const auto scene = std::make_shared<const arcplan::collision::Scene>(
        arcplan::collision::loadScene(arcplan::dataDirectory() / "scenes" / (sceneName + ".yaml")));
    found = problems.emplace(sceneName, arcplan::planners::makePlanningProblem(scene)).first;
  }
  return found->second;
}

// One timed solve from scratch (clear, solve); returns microseconds, aborts the benchmark on failure.
double timedSolve(benchmark::State& state, PlanningProblem& planning, const ompl::base::PlannerPtr& planner) {
  planner->clear();
  planning.setup->getProblemDefinition()->clearSolutionPaths();
  const auto start = std::chrono::steady_clock::now();
  const auto status = planner->solve(ompl::base::timedPlannerTerminationCondition(10.0));
  const double micros = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  if (status != ompl::base::PlannerStatus::EXACT_SOLUTION) state.SkipWithError("planner found no exact solution");
  return micros;
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
  return values[values.size() / 2];
}

ompl::base::PlannerPtr planner(PlanningProblem& planning, const std::string& name, const Parameters& parameters) {
  auto instance = arcplan::planners::makePlanner(name, planning.setup->getSpaceInformation(), planning.plannerContext(),
                                                 parameters);
  instance->setProblemDefinition(planning.setup->getProblemDefinition());
  instance->setup();
  return instance;
}

void solveRepeatedly(benchmark::State& state, const std::string& sceneName, const std::string& name,
                     const Parameters& parameters) {
  PlanningProblem& planning = problem(sceneName);
  const auto instance = planner(planning, name, parameters);
  std::vector<double> times;
  for (auto _ : state) times.push_back(timedSolve(state, planning, instance));
  state.counters["median_us"] = median(times);
}

const Parameters kThesisShape{
    {"sagitta", "0.1"}, {"half_chord", "0.2"}, {"entry_radius", "0.1"}, {"exit_radius", "0.2"}};

void PlannerArcThesisShape(benchmark::State& state) { solveRepeatedly(state, "thesis_obstacle", "arc", kThesisShape); }
BENCHMARK(PlannerArcThesisShape)->Unit(benchmark::kMicrosecond);

// Only the waypoints validated (check_motions = 0), as MoveIt validates Cartesian paths.
void PlannerArcThesisShapeWaypointsOnly(benchmark::State& state) {
  Parameters parameters = kThesisShape;
  parameters.emplace_back("check_motions", "0");
  solveRepeatedly(state, "thesis_obstacle", "arc", parameters);
}
BENCHMARK(PlannerArcThesisShapeWaypointsOnly)->Unit(benchmark::kMicrosecond);

// The thesis' waypoint spacing (5 cm), every motion validated.
void PlannerArcThesisShapeFiveCentimetres(benchmark::State& state) {
  Parameters parameters = kThesisShape;
  parameters.emplace_back("resolution", "0.05");
  solveRepeatedly(state, "thesis_obstacle", "arc", parameters);
}
BENCHMARK(PlannerArcThesisShapeFiveCentimetres)->Unit(benchmark::kMicrosecond);

void PlannerArcAuto(benchmark::State& state) { solveRepeatedly(state, "thesis_obstacle", "arc", {}); }
BENCHMARK(PlannerArcAuto)->Unit(benchmark::kMicrosecond);

void PlannerArcStraightLine(benchmark::State& state) { solveRepeatedly(state, "thesis_free", "arc", {}); }
BENCHMARK(PlannerArcStraightLine)->Unit(benchmark::kMicrosecond);

void PlannerRRTConnect(benchmark::State& state) { solveRepeatedly(state, "thesis_obstacle", "RRTConnect", {}); }
BENCHMARK(PlannerRRTConnect)->Unit(benchmark::kMicrosecond);

// Both planners on the same problem, alternating, so that machine load affects them alike. Besides
// the solve times it reports RRTConnect's time to the path `arcplan plan` and the benchmark execute:
// solve plus OMPL's path simplifier (the arc path needs none), and the ratio to that.
// Argument: 0 the arc planner's auto mode, 1 the thesis shape, 5 the thesis shape with 5 cm waypoints.
void PlannerArcVsRRTConnect(benchmark::State& state) {
  PlanningProblem& planning = problem("thesis_obstacle");
  Parameters arcParameters = state.range(0) == 0 ? Parameters{} : kThesisShape;
  if (state.range(0) == 5) arcParameters.emplace_back("resolution", "0.05");
  const auto arc = planner(planning, "arc", arcParameters);
  const auto rrtConnect = planner(planning, "RRTConnect", {});
  std::vector<double> arcTimes, rrtConnectTimes, rrtConnectSimplifiedTimes;
  for (auto _ : state) {
    arcTimes.push_back(timedSolve(state, planning, arc));
    const double solveMicros = timedSolve(state, planning, rrtConnect);
    const auto start = std::chrono::steady_clock::now();
    planning.setup->simplifySolution();
    rrtConnectTimes.push_back(solveMicros);
    rrtConnectSimplifiedTimes.push_back(
        solveMicros + std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
  }
  state.counters["arc_median_us"] = median(arcTimes);
  state.counters["rrtconnect_median_us"] = median(rrtConnectTimes);
  state.counters["rrtconnect_simplified_median_us"] = median(rrtConnectSimplifiedTimes);
  state.counters["speedup"] = median(rrtConnectTimes) / median(arcTimes);
  state.counters["speedup_to_simplified_path"] = median(rrtConnectSimplifiedTimes) / median(arcTimes);
}
BENCHMARK(PlannerArcVsRRTConnect)
    ->Arg(0)
    ->Arg(1)
    ->Arg(5)
    ->ArgName("auto0_or_waypoint_spacing_cm")
    ->Unit(benchmark::kMicrosecond)
    ->Iterations(400);

}  // namespace
