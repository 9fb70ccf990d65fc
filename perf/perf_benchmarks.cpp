// Benchmarks module: ranking a campaign's runs and generating seeded problems.
#include <benchmark/benchmark.h>

#include "arcplan/benchmarks/generated_problems.h"
#include "arcplan/benchmarks/ranking.h"

namespace {

using namespace arcplan::benchmarks;

// The generated suite's shape: 50 problems x 11 planners x `runs` runs, a quarter of them failed.
void BM_RankRuns(benchmark::State& state) {
  const int runs = static_cast<int>(state.range(0));
  arcplan::benchmarks::CampaignRuns data;
  for (int p = 0; p < 50; ++p) {
    for (int q = 0; q < 11; ++q) {
      auto& list = data["problem" + std::to_string(p)]["planner" + std::to_string(q)];
      for (int r = 0; r < runs; ++r) {
        if ((p + q + r) % 4 == 0) {
          list.push_back({});
        } else {
          const double t = 3.0 + 0.01 * ((p * 7 + q * 13 + r * 3) % 97);
          list.push_back({true, {{"execution_time_s", t}, {"tcp_path_length_m", 0.25 * t}, {"solve_time_s", 0.01}}});
        }
      }
    }
  }
  for (auto _ : state) benchmark::DoNotOptimize(rankRuns(data));
  state.SetItemsProcessed(state.iterations() * 50 * 11 * runs);
}
BENCHMARK(BM_RankRuns)->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond);

void BM_GenerateLineProblems(benchmark::State& state) {
  GeneratorSettings settings;
  settings.seed = 20240611;
  settings.lineObstacles = static_cast<int>(state.range(0));
  settings.pillars = 0;
  settings.shelves = 0;
  for (auto _ : state) benchmark::DoNotOptimize(generateProblems(settings));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_GenerateLineProblems)->Arg(10)->Unit(benchmark::kMillisecond);

}  // namespace
