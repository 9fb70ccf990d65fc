// Collision queries on MotionBenchMaker's UR5 + Robotiq 85 (../shared/data/mbm_ur5; registered only
// when that folder exists): every 10th of the 500 problems, 20 seeded random states per problem
// inside the joint limits, and 10 motions of 0.3 rad (Euclidean, random direction) from
// collision-free random states. The suite plans at 1 cm clearance, so the state check is
// "clearance >= 1 cm?" and motions are certified with minimumClearance 1 cm. Each query is timed on
// its own in thread CPU time (the machine is shared: wall times are several times longer under
// load); counters median_us and p95_us are over queries (what issue 22's goals refer to), plus the
// share that answered free / clear. Models: "exact" = FCL on the meshes only (`--collision
// exact-only`), "spheres" = the sphere prefilter in front of it, "layered" = spheres and convex
// hulls (the default model). CollisionMbmAgreement counts answers that differ from FCL's (10^5 states).
// Run: build/perf/arcplan_perf --benchmark_filter=CollisionMbm
#include <algorithm>
#include <ctime>
#include <filesystem>
#include <functional>
#include <random>

#include <benchmark/benchmark.h>

#include "arcplan/benchmarks/moveit_problems.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/common/resources.h"
#include "support/random_joint_state.h"

namespace {

using namespace arcplan::collision;
using arcplan::testing::randomJointState;
namespace fs = std::filesystem;

constexpr double kClearance = 0.01;
constexpr int kStatesPerProblem = 20, kMotionsPerProblem = 10, kProblemStride = 10;

fs::path mbmFolder() { return arcplan::sharedDataDirectory() / "mbm_ur5"; }

const std::vector<Scene>& mbmScenes() {
  static const std::vector<Scene> scenes = [] {
    const MoveItRobot robot{mbmFolder() / "ur5.urdf", mbmFolder() / "ur5.srdf"};
    const auto files = arcplan::benchmarks::listMoveItProblems(mbmFolder() / "problems");
    std::vector<Scene> result;
    for (std::size_t k = 0; k < files.size(); k += kProblemStride)
      result.push_back(loadMoveItProblem(files[k].scene, files[k].request, robot).scene);
    return result;
  }();
  return scenes;
}

enum class Layers { Exact, Spheres, Layered };
const char* const kLayerNames[] = {"exact", "spheres", "layered"};

// One model per scene, built once per variant.
const std::vector<std::shared_ptr<const CollisionModel>>& models(Layers layers) {
  static const auto make = [](Layers wanted) {
    CollisionModelOptions options;
    options.spherePrefilter = wanted != Layers::Exact;
    options.hullLayer = wanted == Layers::Layered;
    std::vector<std::shared_ptr<const CollisionModel>> result;
    for (const auto& scene : mbmScenes()) result.push_back(makeCollisionModel(scene, options));
    return result;
  };
  static const std::vector<std::shared_ptr<const CollisionModel>> variants[] = {
      make(Layers::Exact), make(Layers::Spheres), make(Layers::Layered)};
  return variants[static_cast<int>(layers)];
}

struct Sample {
  std::size_t scene;
  Eigen::VectorXd start, end;  // end unused for states
};

const std::vector<Sample>& stateSamples() {
  static const std::vector<Sample> samples = [] {
    std::vector<Sample> result;
    std::mt19937_64 random(31);
    for (std::size_t s = 0; s < mbmScenes().size(); ++s) {
      for (int k = 0; k < kStatesPerProblem; ++k)
        result.push_back({s, randomJointState(models(Layers::Exact)[s]->robot(), random), {}});
    }
    return result;
  }();
  return samples;
}

const std::vector<Sample>& motionSamples() {
  static const std::vector<Sample> samples = [] {
    std::vector<Sample> result;
    std::mt19937_64 random(37);
    std::normal_distribution<double> gaussian;
    for (std::size_t s = 0; s < mbmScenes().size(); ++s) {
      const CollisionModel& model = *models(Layers::Exact)[s];
      CollisionData data(model);
      for (int found = 0; found < kMotionsPerProblem;) {
        const Eigen::VectorXd start = randomJointState(model.robot(), random);
        Eigen::VectorXd direction(start.size());
        for (int j = 0; j < direction.size(); ++j) direction[j] = gaussian(random);
        const Eigen::VectorXd end = start + 0.3 * direction.normalized();
        bool inside = true;
        for (int j = 0; j < end.size(); ++j) {
          const auto& limits = model.robot().joints()[j].limits;
          inside = inside && limits.lower <= end[j] && end[j] <= limits.upper;
        }
        if (!inside || !isCollisionFree(model, data, start)) continue;
        result.push_back({s, start, end});
        ++found;
      }
    }
    return result;
  }();
  return samples;
}

using Query = std::function<bool(const CollisionModel&, CollisionData&, const Sample&)>;

double threadCpuMicroseconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return 1e6 * static_cast<double>(now.tv_sec) + 1e-3 * static_cast<double>(now.tv_nsec);
}

// Times every sample's query alone (median of 3 calls) and reports median/95th over samples.
void timeQueries(benchmark::State& state, Layers layers, const std::vector<Sample>& samples, const Query& query) {
  const auto& variant = models(layers);
  std::vector<std::unique_ptr<CollisionData>> data;
  for (const auto& model : variant) data.push_back(std::make_unique<CollisionData>(*model));
  std::vector<double> times;
  std::size_t positive = 0;
  for (auto _ : state) {
    times.clear();
    positive = 0;
    for (const Sample& sample : samples) {
      double calls[3];
      bool answer = false;
      for (double& call : calls) {
        const double begin = threadCpuMicroseconds();
        answer = query(*variant[sample.scene], *data[sample.scene], sample);
        call = threadCpuMicroseconds() - begin;
      }
      std::sort(std::begin(calls), std::end(calls));
      times.push_back(calls[1]);
      positive += answer;
    }
  }
  std::sort(times.begin(), times.end());
  state.counters["median_us"] = times[times.size() / 2];
  state.counters["p95_us"] = times[times.size() * 95 / 100];
  state.counters["positive_fraction"] = static_cast<double>(positive) / static_cast<double>(samples.size());
}

void CollisionMbmState(benchmark::State& state, Layers layers) {
  timeQueries(state, layers, stateSamples(), [](const CollisionModel& model, CollisionData& data, const Sample& s) {
    return isCollisionFree(model, data, s.start);
  });
}

// The 1 cm state check as a full distance query (as OMPL's validity checker asked it before
// hasClearance) and as hasClearance.
void CollisionMbmDistance(benchmark::State& state, Layers layers) {
  timeQueries(state, layers, stateSamples(), [](const CollisionModel& model, CollisionData& data, const Sample& s) {
    return clearanceOf(distance(model, data, s.start)) >= kClearance;
  });
}

void CollisionMbmClearance(benchmark::State& state, Layers layers) {
  timeQueries(state, layers, stateSamples(), [](const CollisionModel& model, CollisionData& data, const Sample& s) {
    return hasClearance(model, data, s.start, kClearance);
  });
}

void CollisionMbmMotion(benchmark::State& state, Layers layers) {
  MotionCheckOptions options;
  options.minimumClearance = kClearance;
  timeQueries(state, layers, motionSamples(),
              [options](const CollisionModel& model, CollisionData& data, const Sample& s) {
                return isMotionCollisionFree(model, data, s.start, s.end, nullptr, options);
              });
}

// "Answers identical to FCL" on MBM: 2000 seeded random states in each of the 50 scenes (10^5 states;
// FCL alone takes ~5 ms per clearance answer), the default model's isCollisionFree and
// hasClearance(1 cm) against FCL on the meshes alone. Counters: disagreements (must be 0), states,
// free and clear fractions.
void CollisionMbmAgreement(benchmark::State& state) {
  std::int64_t disagreements = 0, checked = 0, free = 0, clear = 0;
  for (auto _ : state) {
    for (std::size_t s = 0; s < mbmScenes().size(); ++s) {
      const CollisionModel &layered = *models(Layers::Layered)[s], &exact = *models(Layers::Exact)[s];
      CollisionData layeredData(layered), exactData(exact);
      std::mt19937_64 random(2000 + s);
      for (int k = 0; k < 2000; ++k) {
        const Eigen::VectorXd q = randomJointState(exact.robot(), random);
        const bool expectedFree = isCollisionFree(exact, exactData, q);
        const bool expectedClear = expectedFree && hasClearance(exact, exactData, q, kClearance);
        disagreements += isCollisionFree(layered, layeredData, q) != expectedFree;
        disagreements += hasClearance(layered, layeredData, q, kClearance) != expectedClear;
        free += expectedFree;
        clear += expectedClear;
        ++checked;
      }
    }
  }
  state.counters["disagreements"] = static_cast<double>(disagreements);
  state.counters["states"] = static_cast<double>(checked);
  state.counters["free_fraction"] = static_cast<double>(free) / static_cast<double>(checked);
  state.counters["clear_fraction"] = static_cast<double>(clear) / static_cast<double>(checked);
}

// Registered only where the shared data is.
const bool registered = [] {
  if (!fs::exists(mbmFolder() / "problems")) return false;
  for (const Layers layers : {Layers::Exact, Layers::Spheres, Layers::Layered}) {
    const std::string variant = kLayerNames[static_cast<int>(layers)];
    for (const auto& [name, function] : {std::pair{"CollisionMbmState/", CollisionMbmState},
                                         {"CollisionMbmClearance/", CollisionMbmClearance},
                                         {"CollisionMbmDistance/", CollisionMbmDistance},
                                         {"CollisionMbmMotion/", CollisionMbmMotion}}) {
      benchmark::RegisterBenchmark((name + variant).c_str(), function, layers)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
  }
  benchmark::RegisterBenchmark("CollisionMbmAgreement", CollisionMbmAgreement)->Iterations(1)->Unit(benchmark::kSecond);
  return true;
}();

}  // namespace
