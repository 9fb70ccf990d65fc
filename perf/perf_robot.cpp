// Micro-benchmarks: forward kinematics, Jacobian and analytic IK of the UR10e.
#include <random>

#include <benchmark/benchmark.h>

#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace {

using arcplan::robot::Vector6;

Vector6 randomConfiguration(std::mt19937& random) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  Vector6 q;
  for (auto& v : q) v = angle(random);
  return q;
}

void forwardKinematicsAllLinks(benchmark::State& state) {
  const auto& model = arcplan::robot::ur10e();
  arcplan::robot::KinematicsData data(model);
  std::mt19937 random(1);
  const Vector6 q = randomConfiguration(random);
  for (auto _ : state) {
    arcplan::robot::forwardKinematics(model, q, data);
    benchmark::DoNotOptimize(data.linkPoses.back());
  }
}
BENCHMARK(forwardKinematicsAllLinks);

void jacobianAtTip(benchmark::State& state) {
  const auto& model = arcplan::robot::ur10e();
  arcplan::robot::KinematicsData data(model);
  std::mt19937 random(2);
  arcplan::robot::forwardKinematics(model, randomConfiguration(random), data);
  for (auto _ : state) benchmark::DoNotOptimize(arcplan::robot::jacobian(model, data));
}
BENCHMARK(jacobianAtTip);

void inverseKinematicsBranches(benchmark::State& state) {
  const auto& model = arcplan::robot::ur10e();
  const arcplan::robot::UrInverseKinematics ik(model);
  std::mt19937 random(3);
  const auto pose = arcplan::robot::tipPose(model, randomConfiguration(random));
  for (auto _ : state) benchmark::DoNotOptimize(ik.solveBranches(pose));
}
BENCHMARK(inverseKinematicsBranches);

void inverseKinematicsNearest(benchmark::State& state) {
  const auto& model = arcplan::robot::ur10e();
  const arcplan::robot::UrInverseKinematics ik(model);
  std::mt19937 random(4);
  const Vector6 q = randomConfiguration(random);
  const auto pose = arcplan::robot::tipPose(model, q);
  for (auto _ : state) benchmark::DoNotOptimize(ik.solveNearest(pose, q));
}
BENCHMARK(inverseKinematicsNearest);

}  // namespace
