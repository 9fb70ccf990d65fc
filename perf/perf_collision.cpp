// Micro-benchmarks of collision queries per robot state in the thesis scene (table + particle):
// isCollisionFree, collide and distance, for every FCL bounding-volume type, with and without the
// capsule broad phase. Each iteration checks the next of 1000 random collision-free states.
// "naive" sends every non-allowed part pair to FCL (no capsule broad phase). CollisionMotion*
// checks straight joint-space motions, discrete (0.01 rad) vs certified (motion_check.h). "Prefilter"
// variants put the SIMD sphere prefilter in front of FCL (CollisionModelOptions::spherePrefilter);
// the others are FCL only. CollisionPathCertifier certifies dense paths waypoint by waypoint (the arc planner's walks).
// CollisionPrefilterAgreement counts states whose answer differs between the
// two on 10^5 random states per scene (thesis and generated suites): it must report 0 disagreements.
// Run: build/perf/arcplan_perf --benchmark_filter=Collision --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (the medians are the numbers in docs/collision.md)
#include <algorithm>
#include <chrono>
#include <random>

#include <benchmark/benchmark.h>

#include "arcplan/benchmarks/suite.h"
#include "arcplan/collision/batch_check.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/common/resources.h"
#include "support/random_joint_state.h"
#include "support/thesis_paths.h"

namespace {

using namespace arcplan::collision;
using arcplan::testing::randomJointState;

const Scene& thesisScene() {
  static const Scene scene = loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml");
  return scene;
}

enum class StateSet { Valid, Any, NearContact, FreeSpace };

// 1000 random states inside the joint limits (seeded): collision-free ones, any, collision-free
// ones closer than 2 cm to an obstacle or another link (where the narrow phase actually runs), or
// states in free space: at least 5 cm from everything by FCL's exact distance (the issue's "free
// space"; chosen without asking the prefilter).
const std::vector<Eigen::VectorXd>& states(StateSet set) {
  static const auto make = [](StateSet wanted) {
    const auto model = makeCollisionModel(thesisScene());
    CollisionData data(*model);
    std::mt19937_64 random(11 + static_cast<int>(wanted));
    std::vector<Eigen::VectorXd> result;
    while (result.size() < 1000) {
      const Eigen::VectorXd q = randomJointState(model->robot(), random);
      bool keep = wanted == StateSet::Any || isCollisionFree(*model, data, q);
      if (keep && wanted == StateSet::NearContact) keep = distance(*model, data, q).minimum() < 0.02;
      if (keep && wanted == StateSet::FreeSpace) keep = distance(*model, data, q).minimum() >= 0.05;
      if (keep) result.push_back(q);
    }
    return result;
  };
  static const std::vector<Eigen::VectorXd> sets[] = {make(StateSet::Valid), make(StateSet::Any),
                                                      make(StateSet::NearContact), make(StateSet::FreeSpace)};
  return sets[static_cast<int>(set)];
}

// Narrow phase of a benchmark variant: a BVH type, or (ConvexGJK) FCL's GJK on fcl::Convex parts.
struct Variant {
  BoundingVolume boundingVolume;
  bool convex;
  bool broadPhase;
  bool prefilter = false;
};

std::shared_ptr<const CollisionModel> collisionModelFor(const Variant& variant) {
  CollisionModelOptions options;
  options.collisionBoundingVolume = variant.boundingVolume;
  options.convexCollision = variant.convex;
  options.broadPhase = variant.broadPhase;
  options.spherePrefilter = variant.prefilter;
  return makeCollisionModel(thesisScene(), options);
}

std::shared_ptr<const CollisionModel> distanceModelFor(const Variant& variant) {
  CollisionModelOptions options;
  options.distanceBoundingVolume = variant.boundingVolume;
  options.convexDistance = variant.convex;
  options.broadPhase = variant.broadPhase;
  options.spherePrefilter = variant.prefilter;
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
void CollisionIsCollisionFreePerStateMedian(benchmark::State& state, bool prefilter) {
  CollisionModelOptions options;
  options.spherePrefilter = prefilter;
  const auto model = makeCollisionModel(thesisScene(), options);
  CollisionData data(*model);
  const auto& qs = states(StateSet::Valid);
  std::vector<double> perState;
  for (auto _ : state) {
    perState.clear();
    for (const auto& q : qs) {
      const auto start = std::chrono::steady_clock::now();
      for (int repetition = 0; repetition < 20; ++repetition)
        benchmark::DoNotOptimize(isCollisionFree(*model, data, q));
      perState.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() /
                         20);
    }
  }
  std::nth_element(perState.begin(), perState.begin() + perState.size() / 2, perState.end());
  state.counters["median_us"] = perState[perState.size() / 2];
}
BENCHMARK_CAPTURE(CollisionIsCollisionFreePerStateMedian, exact, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(CollisionIsCollisionFreePerStateMedian, prefilter, true)->Unit(benchmark::kMillisecond);

// States checked 8 at a time (areCollisionFree); items_per_second counts states.
void CollisionStateBatch(benchmark::State& state, bool prefilter, StateSet set) {
  CollisionModelOptions options;
  options.spherePrefilter = prefilter;
  const auto model = makeCollisionModel(thesisScene(), options);
  CollisionData data(*model);
  const auto& qs = states(set);
  Eigen::MatrixXd all(6, static_cast<Eigen::Index>(qs.size()));
  for (std::size_t k = 0; k < qs.size(); ++k) all.col(static_cast<Eigen::Index>(k)) = qs[k];
  std::vector<bool> free;
  std::size_t k = 0, checked = 0;
  for (auto _ : state) {
    areCollisionFree(*model, data, all.middleCols(static_cast<Eigen::Index>(k), 8), free);
    k = (k + 8) % (qs.size() - 8);
    checked += 8;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(checked));
}
BENCHMARK_CAPTURE(CollisionStateBatch, exact_valid, false, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionStateBatch, prefilter_valid, true, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionStateBatch, prefilter_any, true, StateSet::Any);
BENCHMARK_CAPTURE(CollisionStateBatch, prefilter_near, true, StateSet::NearContact);
BENCHMARK_CAPTURE(CollisionStateBatch, exact_free_space, false, StateSet::FreeSpace);
BENCHMARK_CAPTURE(CollisionStateBatch, prefilter_free_space, true, StateSet::FreeSpace);

// The full-count check of "answers identical to FCL": 10^5 seeded random states per scene, the
// prefiltered model's batch answers against FCL-only isCollisionFree. Counters: disagreements (must
// be 0), scenes, states, and the share of collision-free states.
std::vector<Scene> agreementScenes(const std::string& suite) {
  if (suite == "thesis") return {thesisScene(), loadScene(arcplan::dataDirectory() / "scenes" / "thesis_free.yaml")};
  std::vector<Scene> scenes;
  for (const auto& problem : arcplan::benchmarks::loadSuite(arcplan::benchmarks::findSuite(suite)).problems)
    scenes.push_back(problem.scene);
  return scenes;
}

void CollisionPrefilterAgreement(benchmark::State& state, const std::string& suite) {
  const auto scenes = agreementScenes(suite);
  std::int64_t disagreements = 0, checked = 0, valid = 0;
  for (auto _ : state) {
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      CollisionModelOptions exactOnly;
      exactOnly.spherePrefilter = false;
      exactOnly.hullLayer = false;
      const auto fast = makeCollisionModel(scenes[s]), exact = makeCollisionModel(scenes[s], exactOnly);
      CollisionData fastData(*fast), exactData(*exact);
      std::mt19937_64 random(1000 + s);
      Eigen::MatrixXd batch(6, 1000);
      std::vector<bool> free;
      for (int round = 0; round < 100; ++round) {
        for (Eigen::Index k = 0; k < batch.cols(); ++k) batch.col(k) = randomJointState(fast->robot(), random);
        areCollisionFree(*fast, fastData, batch, free);
        for (Eigen::Index k = 0; k < batch.cols(); ++k) {
          const bool expected = isCollisionFree(*exact, exactData, batch.col(k));
          disagreements += free[k] != expected;
          valid += expected;
        }
        checked += batch.cols();
      }
    }
  }
  state.counters["disagreements"] = static_cast<double>(disagreements);
  state.counters["scenes"] = static_cast<double>(scenes.size());
  state.counters["states"] = static_cast<double>(checked);
  state.counters["valid_fraction"] = static_cast<double>(valid) / static_cast<double>(checked);
}
BENCHMARK_CAPTURE(CollisionPrefilterAgreement, thesis, std::string("thesis"))->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(CollisionPrefilterAgreement, generated, std::string("generated"))
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

enum class MotionSet { Long, LongFree, Short };

// 500 seeded motions from collision-free random states: RRT-like (Euclidean joint-space length 1–5
// rad, end anywhere inside the limits), the collision-free ones among such motions (by a 0.001 rad
// discrete check), and arc-path-like segments (largest joint step 0.05 rad, both ends collision-free).
const std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>>& motions(MotionSet set) {
  static const auto make = [](MotionSet wanted) {
    const auto model = makeCollisionModel(thesisScene());
    CollisionData data(*model);
    const auto& joints = model->robot().joints();
    std::mt19937_64 random(23 + static_cast<int>(wanted));
    std::normal_distribution<double> gaussian;
    MotionCheckOptions fine;
    fine.method = MotionCheck::Discrete;
    fine.maxJointStep = 0.001;
    std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> result;
    while (result.size() < 500) {
      Eigen::VectorXd start(6), direction(6);
      for (int j = 0; j < 6; ++j) {
        start[j] = std::uniform_real_distribution<double>(joints[j].limits.lower, joints[j].limits.upper)(random);
        direction[j] = gaussian(random);
      }
      if (!isCollisionFree(*model, data, start)) continue;
      const double scale = wanted == MotionSet::Short
                               ? 0.05 / direction.cwiseAbs().maxCoeff()
                               : std::uniform_real_distribution<double>(1.0, 5.0)(random) / direction.norm();
      const Eigen::VectorXd end = start + scale * direction;
      bool inside = true;
      for (int j = 0; j < 6; ++j)
        inside = inside && joints[j].limits.lower <= end[j] && end[j] <= joints[j].limits.upper;
      if (!inside) continue;
      if (wanted == MotionSet::Short && !isCollisionFree(*model, data, end)) continue;
      if (wanted == MotionSet::LongFree && !isMotionCollisionFree(*model, data, start, end, nullptr, fine)) continue;
      result.emplace_back(start, end);
    }
    return result;
  };
  static const std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> sets[] = {
      make(MotionSet::Long), make(MotionSet::LongFree), make(MotionSet::Short)};
  return sets[static_cast<int>(set)];
}

// Motion checks per second (items_per_second) and the fraction of motions found free.
void CollisionMotion(benchmark::State& state, MotionCheck method, MotionSet set, bool prefilter = false) {
  CollisionModelOptions modelOptions;
  modelOptions.spherePrefilter = prefilter;
  const auto model = makeCollisionModel(thesisScene(), modelOptions);
  CollisionData data(*model);
  MotionCheckOptions options;
  options.method = method;
  const auto& checked = motions(set);
  std::size_t k = 0, free = 0;
  for (auto _ : state) {
    const auto& [start, end] = checked[k++ % checked.size()];
    free += isMotionCollisionFree(*model, data, start, end, nullptr, options);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(k));
  state.counters["free_fraction"] = static_cast<double>(free) / static_cast<double>(k);
}
BENCHMARK_CAPTURE(CollisionMotion, Discrete_long, MotionCheck::Discrete, MotionSet::Long);
BENCHMARK_CAPTURE(CollisionMotion, Certified_long, MotionCheck::Certified, MotionSet::Long);
BENCHMARK_CAPTURE(CollisionMotion, Discrete_long_free, MotionCheck::Discrete, MotionSet::LongFree);
BENCHMARK_CAPTURE(CollisionMotion, Certified_long_free, MotionCheck::Certified, MotionSet::LongFree);
BENCHMARK_CAPTURE(CollisionMotion, Discrete_short, MotionCheck::Discrete, MotionSet::Short);
BENCHMARK_CAPTURE(CollisionMotion, Certified_short, MotionCheck::Certified, MotionSet::Short);
BENCHMARK_CAPTURE(CollisionMotion, Certified_long_prefilter, MotionCheck::Certified, MotionSet::Long, true);
BENCHMARK_CAPTURE(CollisionMotion, Certified_long_free_prefilter, MotionCheck::Certified, MotionSet::LongFree, true);
BENCHMARK_CAPTURE(CollisionMotion, Certified_short_prefilter, MotionCheck::Certified, MotionSet::Short, true);

// Dense paths as the arc planner walks them: 60 seeded paths of 160 small joint steps (0.01–0.02 rad) from the thesis
// query's start to its goal, each bent sideways by a smooth random offset, so that some pass the particle at a few
// centimetres and some within 1 cm; certified at 1 cm with their waypoints expected (PathCertifier::expect), up to the
// first motion refused. Per path: time, motions accepted, measurements per motion.
void CollisionPathCertifier(benchmark::State& state) {
  const auto model = makeCollisionModel(thesisScene());
  CollisionData data(*model);
  std::mt19937_64 random(41);
  std::vector<Eigen::MatrixXd> paths;
  for (int k = 0; k < 60; ++k) {
    const std::vector<Eigen::VectorXd> line = arcplan::testing::bentLine(random, 160);
    Eigen::MatrixXd path(6, static_cast<Eigen::Index>(line.size()));
    for (std::size_t i = 0; i < line.size(); ++i) path.col(static_cast<Eigen::Index>(i)) = line[i];
    paths.push_back(path);
  }
  std::size_t k = 0, accepted = 0, measurements = 0;
  for (auto _ : state) {
    const Eigen::MatrixXd& path = paths[k++ % paths.size()];
    PathCertifier certifier(*model, data, 0.01);
    certifier.expect(path);
    if (!certifier.start(path.col(0))) continue;
    for (Eigen::Index i = 1; i < path.cols() && certifier.extend(path.col(i)); ++i) ++accepted;
    measurements += static_cast<std::size_t>(certifier.measurements());
  }
  state.counters["motions_accepted_per_path"] = static_cast<double>(accepted) / static_cast<double>(k);
  state.counters["measurements_per_motion"] = static_cast<double>(measurements) / static_cast<double>(accepted);
}
BENCHMARK(CollisionPathCertifier)->Unit(benchmark::kMicrosecond);

using BV = BoundingVolume;
// The default model: ConvexGJK boolean queries and distances with the capsule broad phase.
BENCHMARK_CAPTURE(CollisionIsCollisionFree, ConvexGJK_broad_valid, Variant{BV::OBB, true, true}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, Prefilter_valid, Variant{BV::OBB, true, true, true}, StateSet::Valid);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, Prefilter_any, Variant{BV::OBB, true, true, true}, StateSet::Any);
BENCHMARK_CAPTURE(CollisionIsCollisionFree, Prefilter_near, Variant{BV::OBB, true, true, true}, StateSet::NearContact);
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
