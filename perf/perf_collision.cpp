// Micro-benchmarks of collision queries per robot state in the thesis scene (table + particle):
// isCollisionFree, collide and distance, for every FCL bounding-volume type, with and without the
// capsule broad phase. Each iteration checks the next of 1000 random collision-free states.
// "naive" sends every non-allowed part pair to FCL (no capsule broad phase).
// Run: build/perf/arcplan_perf --benchmark_filter=Collision --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (the medians are the numbers in docs/collision.md)
#include <algorithm>
#include <chrono>
#include <random>

#include <benchmark/benchmark.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/common/resources.h"

namespace {

using namespace arcplan::collision;

const Scene& thesisScene() {
  static const Scene scene = loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml");
  return scene;
}

enum class StateSet { Valid, Any, NearContact };

// 1000 random states inside the joint limits (seeded): collision-free ones, any, or collision-free
// ones closer than 2 cm to an obstacle or another link (where the narrow phase actually runs).
const std::vector<Eigen::VectorXd>& states(StateSet set) {
  static const auto make = [](StateSet wanted) {
    const auto model = makeCollisionModel(thesisScene());
    CollisionData data(*model);
    std::mt19937_64 random(11 + static_cast<int>(wanted));
    std::vector<Eigen::VectorXd> result;
    while (result.size() < 1000) {
      Eigen::VectorXd q(6);
      for (int j = 0; j < 6; ++j) {
        const auto& limits = model->robot().joints()[j].limits;
        q[j] = std::uniform_real_distribution<double>(limits.lower, limits.upper)(random);
      }
      const bool keep = wanted == StateSet::Any ||
                        (isCollisionFree(*model, data, q) &&
                         (wanted == StateSet::Valid || distance(*model, data, q).minimum() < 0.02));
      if (keep) result.push_back(q);
    }
    return result;
  };
  static const std::vector<Eigen::VectorXd> sets[] = {make(StateSet::Valid), make(StateSet::Any),
                                                      make(StateSet::NearContact)};
  return sets[static_cast<int>(set)];
}

// Narrow phase of a benchmark variant: a BVH type, or (ConvexGJK) FCL's GJK on fcl::Convex parts.
struct Variant {
  BoundingVolume boundingVolume;
  bool convex;
  bool broadPhase;
};

std::shared_ptr<const CollisionModel> collisionModelFor(const Variant& variant) {
  CollisionModelOptions options;
  options.collisionBoundingVolume = variant.boundingVolume;
  options.convexCollision = variant.convex;
  options.broadPhase = variant.broadPhase;
  return makeCollisionModel(thesisScene(), options);
}

std::shared_ptr<const CollisionModel> distanceModelFor(const Variant& variant) {
  CollisionModelOptions options;
  options.distanceBoundingVolume = variant.boundingVolume;
  options.convexDistance = variant.convex;
  options.broadPhase = variant.broadPhase;
  return makeCollisionModel(thesisScene(), options);
}

void CollisionIsCollisionFree(benchmark::State& state, Variant variant, StateSet set) {
  const auto model = collisionModelFor(variant);
  CollisionData data(*model);
  const auto& qs = states(set);
  std::size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(isCollisionFree(*model, data, qs[k++ % qs.size()]));
}

void CollisionCollide(benchmark::State& state, Variant variant) {
  const auto model = collisionModelFor(variant);
  CollisionData data(*model);
  const auto& qs = states(StateSet::Valid);
  std::size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(collide(*model, data, qs[k++ % qs.size()]));
}

void CollisionDistance(benchmark::State& state, Variant variant) {
  const auto model = distanceModelFor(variant);
  CollisionData data(*model);
  const auto& qs = states(StateSet::Valid);
  std::size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(distance(*model, data, qs[k++ % qs.size()]));
}

// The per-state median the target refers to: each of the 1000 valid states is timed on its
// own (20 repetitions), and the median over states is reported as the counter median_us.
void CollisionIsCollisionFreePerStateMedian(benchmark::State& state) {
  const auto model = makeCollisionModel(thesisScene());
  CollisionData data(*model);
  const auto& qs = states(StateSet::Valid);
  std::vector<double> perState;
  for (auto _ : state) {
    perState.clear();
    for (const auto& q : qs) {
      const auto start = std::chrono::steady_clock::now();
      for (int repetition = 0; repetition < 20; ++repetition) benchmark::DoNotOptimize(isCollisionFree(*model, data, q));
      perState.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / 20);
    }
  }
  std::nth_element(perState.begin(), perState.begin() + perState.size() / 2, perState.end());
  state.counters["median_us"] = perState[perState.size() / 2];
}
BENCHMARK(CollisionIsCollisionFreePerStateMedian)->Unit(benchmark::kMillisecond);

using BV = BoundingVolume;
// The default model: ConvexGJK boolean queries and distances with the capsule broad phase.
BENCHMARK_CAPTURE(CollisionIsCollisionFree, ConvexGJK_broad_valid, Variant{BV::OBB, true, true}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, ConvexGJK_broad_any, Variant{BV::OBB, true, true}, StateSet::Any);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, OBB_broad_valid, Variant{BV::OBB, false, true}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, AABB_broad_valid, Variant{BV::AABB, false, true}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, RSS_broad_valid, Variant{BV::RSS, false, true}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, kIOS_broad_valid, Variant{BV::kIOS, false, true}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, OBBRSS_broad_valid, Variant{BV::OBBRSS, false, true}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, OBB_broad_any, Variant{BV::OBB, false, true}, StateSet::Any);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, ConvexGJK_broad_near, Variant{BV::OBB, true, true}, StateSet::NearContact);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, OBB_broad_near, Variant{BV::OBB, false, true}, StateSet::NearContact);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, kIOS_broad_near, Variant{BV::kIOS, false, true}, StateSet::NearContact);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, OBBRSS_broad_near, Variant{BV::OBBRSS, false, true}, StateSet::NearContact);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, ConvexGJK_naive_valid, Variant{BV::OBB, true, false}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, OBB_naive_valid, Variant{BV::OBB, false, false}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, AABB_naive_valid, Variant{BV::AABB, false, false}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, RSS_naive_valid, Variant{BV::RSS, false, false}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, kIOS_naive_valid, Variant{BV::kIOS, false, false}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, OBBRSS_naive_valid, Variant{BV::OBBRSS, false, false}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionCollide, ConvexGJK_broad, Variant{BV::OBB, true, true});
BENCHMARK_CAPTURE(CollisionCollide, OBB_broad, Variant{BV::OBB, false, true});
BENCHMARK_CAPTURE(CollisionDistance, ConvexGJK_broad, Variant{BV::OBBRSS, true, true});
BENCHMARK_CAPTURE(CollisionDistance, OBBRSS_broad, Variant{BV::OBBRSS, false, true});
BENCHMARK_CAPTURE(CollisionDistance, RSS_broad, Variant{BV::RSS, false, true});
BENCHMARK_CAPTURE(CollisionDistance, kIOS_broad, Variant{BV::kIOS, false, true});
BENCHMARK_CAPTURE(CollisionDistance, ConvexGJK_naive, Variant{BV::OBBRSS, true, false});
BENCHMARK_CAPTURE(CollisionDistance, OBBRSS_naive, Variant{BV::OBBRSS, false, false});

}  // namespace
