// Model loop speed on a 60 s, 500 Hz UR10e log (30 000 samples x 6 joints): diagnose with discovery
// of new terms must take at most 5 s on 2 cores; compare + diagnose, the catalogue alone, reading
// the log, and the rigid-body dynamics the loop calls per sample.
#include <filesystem>

#include <benchmark/benchmark.h>
#include <unistd.h>

#include "arcplan/model/compare.h"
#include "arcplan/model/diagnose.h"
#include "arcplan/model/simulate.h"
#include "arcplan/robot/dynamics.h"

namespace {

using namespace arcplan::model;

const ModelSpec& baseModel() {
  static const ModelSpec spec = parseModelYaml(
      "kind: joint_current\nload_torque: target_moment\neffects: [drive_gain, offset, coulomb, viscous]\n",
      "base.yaml");
  return spec;
}

// A 60 s, 500 Hz log with a hidden load-dependent friction, written once as RTDE CSV and removed
// at exit.
struct TemporaryLog {
  TemporaryLog()
      : path(std::filesystem::temp_directory_path() / ("arcplan_perf_model_" + std::to_string(::getpid()) + ".csv")) {
    const ModelSpec truth = parseModelYaml(
        "kind: joint_current\nload_torque: target_moment\n"
        "effects: [drive_gain, offset, coulomb, viscous, load_friction]\n",
        "truth.yaml");
    ExcitationOptions excitation;  // 60 s at 500 Hz by default
    Eigen::VectorXd center(6);
    center << 0.0, -M_PI / 2, M_PI / 4, -M_PI / 2, -M_PI / 2, 0.0;
    writeLog(simulateLog(truth, excitationTrajectory(center, excitation), {}), path);
  }
  ~TemporaryLog() { std::filesystem::remove(path); }
  std::filesystem::path path;
};

const std::filesystem::path& sixtySecondLog() {
  static const TemporaryLog log;
  return log.path;
}

// What `arcplan model compare` and `arcplan model diagnose` do on that log, without plots:
// read it, derive accelerations, fit, compare, and rank every catalogue effect and library term by
// 5-fold time-blocked cross-validation.
void compareAndDiagnose60s500Hz(benchmark::State& state) {
  const auto& file = sixtySecondLog();
  for (auto _ : state) {
    const Dataset data = makeJointDataset(readLog(file), baseModel());
    const FittedModel fitted = fitModel(baseModel(), data);
    const Comparison comparison = compareModel(fitted, data, nullptr);
    const Diagnosis diagnosis = diagnose(baseModel(), data, nullptr);
    benchmark::DoNotOptimize(comparison.data.overallNrmse);
    benchmark::DoNotOptimize(diagnosis.ranking.size());
  }
  state.counters["samples"] = 30001;
}
BENCHMARK(compareAndDiagnose60s500Hz)->Unit(benchmark::kMillisecond)->Iterations(3);

// Catalogue effects and the term library (discovery), 5-fold cross-validation.
void diagnoseWithDiscovery60s500HzLoaded(benchmark::State& state) {
  const Dataset data = makeJointDataset(readLog(sixtySecondLog()), baseModel());
  for (auto _ : state) benchmark::DoNotOptimize(diagnose(baseModel(), data, nullptr).ranking.size());
}
BENCHMARK(diagnoseWithDiscovery60s500HzLoaded)->Unit(benchmark::kMillisecond)->Iterations(3);

void diagnoseCatalogueOnly60s500HzLoaded(benchmark::State& state) {
  const Dataset data = makeJointDataset(readLog(sixtySecondLog()), baseModel());
  DiagnoseOptions options;
  options.discover = false;
  for (auto _ : state) benchmark::DoNotOptimize(diagnose(baseModel(), data, nullptr, options).ranking.size());
}
BENCHMARK(diagnoseCatalogueOnly60s500HzLoaded)->Unit(benchmark::kMillisecond)->Iterations(3);

void readLog60s500Hz(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(readLog(sixtySecondLog()).rows());
}
BENCHMARK(readLog60s500Hz)->Unit(benchmark::kMillisecond)->Iterations(3);

void inverseDynamicsUr10e(benchmark::State& state) {
  const auto& model = arcplan::robot::ur10e();
  arcplan::robot::DynamicsData data(model);
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(6, -1.0, 1.0), qd = Eigen::VectorXd::Constant(6, 0.5),
                        qdd = Eigen::VectorXd::Constant(6, -1.0);
  for (auto _ : state) benchmark::DoNotOptimize(arcplan::robot::inverseDynamics(model, q, qd, qdd, data));
}
BENCHMARK(inverseDynamicsUr10e);

}  // namespace
