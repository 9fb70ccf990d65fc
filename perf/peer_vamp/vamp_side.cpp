// The VAMP half of the side-by-side benchmark (see vamp_side.h). Compiled with -march=native into
// its own library with hidden symbols; uses only VAMP's public C++ API as its examples do.
#include "vamp_side.h"

#include <vamp/collision/factory.hh>
#include <vamp/planning/rrtc.hh>
#include <vamp/planning/simplify.hh>
#include <vamp/random/halton.hh>
#include <vamp/robots/ur5.hh>

#include <chrono>
#include <memory>

namespace arcplan::peer_vamp {
namespace {

using Robot = vamp::robots::UR5;
constexpr std::size_t kRake = vamp::FloatVectorWidth;
using EnvironmentInput = vamp::collision::Environment<float>;
using EnvironmentVector = vamp::collision::Environment<vamp::FloatVector<kRake>>;
using Planner = vamp::planning::RRTC<Robot, kRake, Robot::resolution>;

float f(double value) { return static_cast<float>(value); }

// The lists VAMP's Python Environment.add_cuboid / add_capsule choose (a z-aligned shape has a
// cheaper test), then sorted by distance from the origin as VAMP expects.
EnvironmentVector makeEnvironment(const VampScene& scene) {
  EnvironmentInput environment;
  for (const VampCuboid& box : scene.cuboids) {
    const auto& [a1, a2, a3] = box.axes;
    vamp::collision::Cuboid<float> cuboid(f(box.center[0]), f(box.center[1]), f(box.center[2]), f(a1[0]), f(a1[1]),
                                          f(a1[2]), f(a2[0]), f(a2[1]), f(a2[2]), f(a3[0]), f(a3[1]), f(a3[2]),
                                          f(box.halfExtents[0]), f(box.halfExtents[1]), f(box.halfExtents[2]));
    (cuboid.axis_3_z == 1.0F ? environment.z_aligned_cuboids : environment.cuboids).push_back(cuboid);
  }
  for (const VampCapsule& capsule : scene.capsules) {
    const auto shape = vamp::collision::factory::capsule::endpoints::flat(
        f(capsule.end1[0]), f(capsule.end1[1]), f(capsule.end1[2]), f(capsule.end2[0]), f(capsule.end2[1]),
        f(capsule.end2[2]), f(capsule.radius));
    (shape.xv == 0.0F && shape.yv == 0.0F ? environment.z_aligned_capsules : environment.capsules).push_back(shape);
  }
  for (const VampSphere& sphere : scene.spheres) {
    environment.spheres.push_back(vamp::collision::factory::sphere::flat(f(sphere.center[0]), f(sphere.center[1]),
                                                                         f(sphere.center[2]), f(sphere.radius)));
  }
  environment.sort();
  return EnvironmentVector(environment);
}

Robot::Configuration configuration(const Joints& q) {
  Robot::ConfigurationArray values{};
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = f(q[i]);
  return Robot::Configuration(values);
}

Joints joints(const Robot::Configuration& configuration) {
  const auto values = configuration.to_array();
  Joints q{};
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = values[i];
  return q;
}

// VAMP's own single-state check: a motion from q to q puts q in every lane of one block.
bool valid(const EnvironmentVector& environment, const Robot::Configuration& q) {
  return vamp::planning::validate_motion<Robot, kRake, 1>(q, q, environment);
}

}  // namespace

VampRun runVamp(const VampScene& scene, const Joints& start, const Joints& goal, const VampSettings& settings) {
  const EnvironmentVector environment = makeEnvironment(scene);
  const Robot::Configuration startConfiguration = configuration(start);
  const Robot::Configuration goalConfiguration = configuration(goal);
  VampRun run;
  run.startValid = valid(environment, startConfiguration);
  run.goalValid = valid(environment, goalConfiguration);
  if (!run.startValid || !run.goalValid) return run;

  vamp::planning::RRTCSettings rrtc;
  rrtc.range = f(settings.range);
  rrtc.max_iterations = settings.maxIterations;
  rrtc.max_samples = settings.maxIterations;
  const vamp::planning::SimplifySettings simplify;
  // A fresh Halton sequence per problem: what VAMP's evaluation does with sampler.reset().
  auto rng = std::make_shared<vamp::rng::Halton<Robot>>();

  const auto clock = std::chrono::steady_clock::now();
  const auto planned = Planner::solve(startConfiguration, goalConfiguration, environment, rrtc, rng);
  vamp::planning::PlanningResult<Robot> simplified;
  if (!planned.path.empty()) {
    simplified = vamp::planning::simplify<Robot, kRake, Robot::resolution>(planned.path, environment, simplify, rng);
  }
  run.wallUs = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - clock).count();

  run.iterations = planned.iterations;
  run.planningUs = static_cast<double>(planned.nanoseconds) / 1000.0;
  if (planned.path.empty()) return run;
  run.solved = true;
  run.rawWaypoints = planned.path.size();
  run.initialCost = planned.path.cost();
  run.simplificationUs = static_cast<double>(simplified.nanoseconds) / 1000.0;
  run.simplifiedCost = simplified.path.cost();
  for (const auto& q : simplified.path) run.path.push_back(joints(q));
  return run;
}

bool vampStateValid(const VampScene& scene, const Joints& q) { return valid(makeEnvironment(scene), configuration(q)); }

std::array<double, 16> vampEndEffectorPose(const Joints& q) {
  std::array<float, 6> values{};
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = f(q[i]);
  const Eigen::Isometry3f pose = Robot::eefk(values);
  std::array<double, 16> matrix{};
  for (int row = 0; row < 4; ++row) {
    for (int column = 0; column < 4; ++column) matrix[4 * row + column] = pose.matrix()(row, column);
  }
  return matrix;
}

VampRobotInfo vampRobotInfo() {
  VampRobotInfo info{Robot::name, Robot::end_effector, Robot::n_spheres, kRake, Robot::resolution, {}};
  for (const auto& name : Robot::joint_names) info.jointNames.emplace_back(name);
  return info;
}

}  // namespace arcplan::peer_vamp
