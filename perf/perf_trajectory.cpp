// Micro-benchmarks of the time scaling: the benchmark harness scales every planner's path after each
// run, so scaling a 1000-waypoint path must stay within a few milliseconds (issue: <= 5 ms median).
#include <cmath>
#include <stdexcept>

#include <benchmark/benchmark.h>

#include "arcplan/robot/pose.h"
#include "arcplan/robot/ur_inverse_kinematics.h"
#include "arcplan/trajectory/path_densification.h"
#include "arcplan/trajectory/pchip.h"
#include "arcplan/trajectory/time_scaling.h"

namespace {

using arcplan::robot::Vector6;
using arcplan::trajectory::JointPath;

// The thesis line A→B (0.833 m, tool pointing down) by nearest IK at `waypoints` evenly spaced poses.
JointPath thesisLine(int waypoints) {
  const auto& model = arcplan::robot::ur10e();
  const arcplan::robot::UrInverseKinematics ik(model);
  const Eigen::Isometry3d a = arcplan::robot::poseFromXyzRpy({0.4, -0.4, 0.25, 0.0, -M_PI, M_PI / 2});
  const Eigen::Isometry3d b = arcplan::robot::poseFromXyzRpy({0.5, 0.4, 0.46, 0.0, -M_PI, M_PI / 2});
  Vector6 seed;
  seed << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098;
  JointPath path;
  for (int i = 0; i < waypoints; ++i) {
    Eigen::Isometry3d pose = a;
    pose.translation() += (b.translation() - a.translation()) * (double(i) / (waypoints - 1));
    const auto q = ik.solveNearest(pose, seed);
    if (!q) throw std::runtime_error("thesis line out of reach");
    path.push_back(seed = *q);
  }
  return path;
}

// An RRTConnect-like path: 4 waypoints up to ~1 rad apart.
JointPath sparsePath() {
  Vector6 a, m1, m2, b;
  a << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098;
  m1 << -0.6, -1.9, 2.0, -1.5, -1.2, -0.2;
  m2 << 0.1, -1.3, 1.6, -2.2, -1.9, 0.9;
  b << 0.399, -1.624, 2.012, -1.958, -1.571, 0.399;
  return {a, m1, m2, b};
}

void scaleThousandWaypointPath(benchmark::State& state) {
  const auto& model = arcplan::robot::ur10e();
  const JointPath path = thesisLine(1000);
  arcplan::trajectory::TimeScalingOptions options;
  options.maxTcpSpeed = static_cast<double>(state.range(0)) / 1000.0;
  for (auto _ : state) benchmark::DoNotOptimize(arcplan::trajectory::scaleToTcpSpeed(model, path, options));
}
BENCHMARK(scaleThousandWaypointPath)->Arg(250)->Arg(149)->Unit(benchmark::kMillisecond)->Repetitions(5);

void scaleSparsePath(benchmark::State& state) {
  const auto& model = arcplan::robot::ur10e();
  const JointPath path = sparsePath();
  for (auto _ : state) benchmark::DoNotOptimize(arcplan::trajectory::scaleToTcpSpeed(model, path, {}));
}
BENCHMARK(scaleSparsePath)->Unit(benchmark::kMillisecond);

void densifySparsePath(benchmark::State& state) {
  const auto& model = arcplan::robot::ur10e();
  const JointPath path = sparsePath();
  for (auto _ : state) benchmark::DoNotOptimize(arcplan::trajectory::densifyJointPath(model, path));
}
BENCHMARK(densifySparsePath)->Unit(benchmark::kMicrosecond);

void pchipFitThousandKnots(benchmark::State& state) {
  const JointPath path = thesisLine(1000);
  std::vector<double> knots(path.size());
  Eigen::MatrixXd values(path.size(), 6);
  for (std::size_t k = 0; k < path.size(); ++k) {
    knots[k] = 0.004 * k;
    values.row(k) = path[k].transpose();
  }
  arcplan::trajectory::Pchip pchip;
  for (auto _ : state) {
    pchip.fit(knots, values, arcplan::trajectory::PchipEnds::ZeroSlope);
    benchmark::DoNotOptimize(pchip.slopes().data());
  }
}
BENCHMARK(pchipFitThousandKnots)->Unit(benchmark::kMicrosecond);

}  // namespace
