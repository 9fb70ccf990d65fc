// The C++ side of the Python module's overhead (docs/python.md): the same calls the bindings make,
// on the same inputs, so that perf/python_overhead.py can compare them with the Python calls.
//   PythonBaselineIsValidBatch: collision::areCollisionFree on 10^5 states of the thesis scene in one
//     call (what Scene.is_valid(Q) runs); the states come from the formula python_overhead.py uses.
//   PythonBaselinePlanTrivial: benchmarks::planQuery on perf/python_trivial_query.yaml (what
//     arcplan.plan(scene, planner=...) runs).
// Run: build/python/arcplan_perf_python --benchmark_repetitions=5 (or perf/python_overhead.py).
#include <benchmark/benchmark.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "arcplan/benchmarks/plan_query.h"
#include "arcplan/collision/batch_check.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/common/resources.h"

namespace {

// q[k, j] = -pi + 2 pi frac((6 k + j + 1) * 0.618...): spread over [-pi, pi), about half of them in
// collision; python_overhead.py computes the same numbers with NumPy.
Eigen::MatrixXd stateColumns(int count) {
  Eigen::MatrixXd states(6, count);
  for (int k = 0; k < count; ++k) {
    for (int j = 0; j < 6; ++j) {
      const double index = 6.0 * k + j + 1.0;
      states(j, k) = -M_PI + 2.0 * M_PI * std::fmod(index * 0.6180339887498949, 1.0);
    }
  }
  return states;
}

void PythonBaselineIsValidBatch(benchmark::State& state) {
  const auto scene = arcplan::collision::loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml");
  const auto model = arcplan::collision::makeCollisionModel(scene);
  arcplan::collision::CollisionData data(*model);
  const Eigen::MatrixXd states = stateColumns(100000);
  std::vector<bool> free;
  for (auto _ : state) {
    arcplan::collision::areCollisionFree(*model, data, states, free);
    benchmark::DoNotOptimize(free);
  }
  state.SetItemsProcessed(state.iterations() * states.cols());
}
BENCHMARK(PythonBaselineIsValidBatch)->Unit(benchmark::kMillisecond);

// Every call timed: under load the mean says more about the machine than about the call, so the
// fastest and the median call are reported too (counters min_us, median_us).
void PythonBaselinePlanTrivial(benchmark::State& state, const char* planner) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const auto scene = std::make_shared<const arcplan::collision::Scene>(
      arcplan::collision::loadScene(ARCPLAN_PERF_DIR "/python_trivial_query.yaml"));
  arcplan::benchmarks::PlanQueryOptions options;
  options.planner = planner;
  std::vector<double> times;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const auto planned = arcplan::benchmarks::planQuery(scene, "", options);
    times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
    if (planned.status != arcplan::benchmarks::PlanStatus::Exact) state.SkipWithError("no exact path");
  }
  std::sort(times.begin(), times.end());
  state.counters["min_us"] = times.front();
  state.counters["median_us"] = times[times.size() / 2];
}
// 200 calls per repetition, as python_overhead.py makes: the fastest of n calls depends on n.
BENCHMARK_CAPTURE(PythonBaselinePlanTrivial, arc, "arc")->Iterations(200)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(PythonBaselinePlanTrivial, RRTConnect, "RRTConnect")->Iterations(200)->Unit(benchmark::kMicrosecond);

}  // namespace
