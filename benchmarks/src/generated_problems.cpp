#include "arcplan/benchmarks/generated_problems.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <random>

#include "arcplan/common/error.h"
#include "problem_factory.h"

namespace arcplan::benchmarks {
namespace {

using namespace detail;

// One sphere, box or cylinder on or near the straight line (the thesis' situation, randomised).
Problem lineObstacleProblem(const ProblemFactory& factory, std::uint64_t seed, int index) {
  static const char* kinds[] = {"sphere", "box", "cylinder"};
  const std::string shape = kinds[index % 3];
  Random random(streamSeed(seed, 1, static_cast<std::uint64_t>(index)));
  for (int attempt = 0; attempt < kAttemptsPerProblem; ++attempt) {
    const Vector3d a = workspacePoint(random, 0.15, 0.55);
    const Vector3d b = workspacePoint(random, 0.15, 0.55);
    const double length = (b - a).norm();
    if (length < 0.45 || length > 1.0 || distanceFromBaseAxis(a, b) < 0.35) continue;

    collision::Obstacle obstacle;
    obstacle.name = "obstacle";
    Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();
    if (shape == "sphere") {
      obstacle.shape = collision::Obstacle::Shape::Sphere;
      obstacle.radius = random.uniform(0.01, 0.08);
    } else if (shape == "box") {
      obstacle.shape = collision::Obstacle::Shape::Box;
      obstacle.size = Vector3d(random.uniform(0.03, 0.15), random.uniform(0.03, 0.15), random.uniform(0.03, 0.15));
      orientation = robot::rotationFromRpy(0.0, 0.0, random.uniform(-M_PI, M_PI));
    } else {
      obstacle.shape = collision::Obstacle::Shape::Cylinder;
      obstacle.radius = random.uniform(0.015, 0.06);
      obstacle.length = random.uniform(0.05, 0.25);
      orientation = robot::rotationFromRpy(random.uniform(-M_PI, M_PI), random.uniform(-M_PI / 2, M_PI / 2), 0.0);
    }
    obstacle.pose.linear() = orientation;
    obstacle.pose.translation() = Vector3d::Zero();
    const double bound = obstacle.boundingRadius();
    // "On or near": the centre is up to 1.2 bounding radii off the line, so some lines stay free.
    const Vector3d onLine = a + random.uniform(0.3, 0.7) * (b - a);
    const Vector3d center = onLine + random.uniform(0.0, 1.2 * bound) * randomPerpendicular(random, b - a);
    obstacle.pose.translation() = center;
    if (center.z() - bound < 0.01) continue;                                                 // clear of the table
    if ((center - a).norm() < bound + 0.15 || (center - b).norm() < bound + 0.15) continue;  // room for a detour

    const auto ends = factory.straightLineEnds(a, b);
    if (!ends) continue;
    auto scene = tableScene("");
    scene.obstacles.push_back(obstacle);
    if (!factory.collisionFree(scene, *ends)) continue;
    setQuery(scene, *ends);
    return makeProblem(indexed("line-" + shape, index), "line-" + shape, seed, index, std::move(scene));
  }
  throw Error("problem generator: no valid line-" + shape + " problem " + std::to_string(index) + " for seed " +
              std::to_string(seed) + " after " + std::to_string(kAttemptsPerProblem) + " attempts");
}

// Sizes of a pillar or shelf family.
struct FurnitureFamily {
  const char* kind;
  std::uint64_t stream;
  double low, high;  // pillar: radius; shelf: depth (m)
  double height;     // pillar height (m); unused for shelves
};
const FurnitureFamily kPillars{"pillar", 2, 0.05, 0.09, 1.6};
const FurnitureFamily kTallPillars{"pillar-tall", 8, 0.08, 0.14, 2.0};
const FurnitureFamily kShelves{"shelf", 3, 0.25, 0.35, 0.0};
const FurnitureFamily kDeepShelves{"shelf-deep", 9, 0.38, 0.45, 0.0};

// A floor-to-ceiling column across the line: an arc of bounded height cannot clear it.
Problem pillarProblem(const ProblemFactory& factory, std::uint64_t seed, int index, const FurnitureFamily& family) {
  Random random(streamSeed(seed, family.stream, static_cast<std::uint64_t>(index)));
  for (int attempt = 0; attempt < kAttemptsPerProblem; ++attempt) {
    const Vector3d a = workspacePoint(random, 0.15, 0.5);
    const Vector3d b = workspacePoint(random, 0.15, 0.5);
    const double length = (b - a).norm();
    if (length < 0.6 || length > 1.1 || distanceFromBaseAxis(a, b) < 0.4) continue;
    const double radius = random.uniform(family.low, family.high);
    const double height = family.height;
    Vector3d center = a + random.uniform(0.4, 0.6) * (b - a);
    center += random.uniform(0.0, 0.5 * radius) *
              randomPerpendicular(random, Vector3d(b - a).cwiseProduct(Vector3d(1, 1, 0)));
    center.z() = height / 2;
    const auto horizontal = [&](const Vector3d& p) { return (p - center).head<2>().norm(); };
    if (horizontal(a) < radius + 0.2 || horizontal(b) < radius + 0.2) continue;
    if (center.head<2>().norm() < radius + 0.3) continue;  // not on top of the robot base

    const auto ends = factory.straightLineEnds(a, b);
    if (!ends) continue;
    auto scene = tableScene("");
    collision::Obstacle pillar;
    pillar.name = "pillar";
    pillar.shape = collision::Obstacle::Shape::Cylinder;
    pillar.radius = radius;
    pillar.length = height;
    pillar.pose = Eigen::Isometry3d::Identity();
    pillar.pose.translation() = center;
    scene.obstacles.push_back(pillar);
    if (!factory.collisionFree(scene, *ends)) continue;
    setQuery(scene, *ends);
    return makeProblem(indexed(family.kind, index), family.kind, seed, index, std::move(scene));
  }
  throw Error(std::string("problem generator: no valid ") + family.kind + " problem " + std::to_string(index) +
              " for seed " + std::to_string(seed));
}

// A shelf unit (side panels, three boards, back panel facing the start) across the line: the tool
// has to go over or around a wall-like obstacle much larger than any arc detour.
Problem shelfProblem(const ProblemFactory& factory, std::uint64_t seed, int index, const FurnitureFamily& family) {
  Random random(streamSeed(seed, family.stream, static_cast<std::uint64_t>(index)));
  constexpr double panel = 0.02;
  for (int attempt = 0; attempt < kAttemptsPerProblem; ++attempt) {
    const Vector3d a = workspacePoint(random, 0.12, 0.3);
    const Vector3d b = workspacePoint(random, 0.12, 0.3);
    const double length = (b - a).head<2>().norm();
    if (length < 0.65 || length > 1.1 || distanceFromBaseAxis(a, b) < 0.45) continue;
    const double width = random.uniform(0.4, 0.6), depth = random.uniform(family.low, family.high);
    const double height = random.uniform(0.55, 0.8);
    const Vector3d middle = 0.5 * (a + b);
    const double yaw = std::atan2(b.y() - a.y(), b.x() - a.x());  // shelf x axis along the line's projection
    if (middle.head<2>().norm() < 0.5 * std::hypot(width, depth) + 0.25) continue;

    const Eigen::Matrix3d rotation = robot::rotationFromRpy(0.0, 0.0, yaw);
    const auto at = [&](double x, double y, double z) -> Vector3d {
      return Vector3d(middle.x(), middle.y(), 0.0) + rotation * Vector3d(x, y, z);
    };
    auto scene = tableScene("");
    scene.obstacles.push_back(
        box("shelf_back", Vector3d(panel, width, height), at(depth / 2 - panel / 2, 0, height / 2), yaw));
    scene.obstacles.push_back(
        box("shelf_left", Vector3d(depth, panel, height), at(0, width / 2 - panel / 2, height / 2), yaw));
    scene.obstacles.push_back(
        box("shelf_right", Vector3d(depth, panel, height), at(0, -width / 2 + panel / 2, height / 2), yaw));
    for (const auto& [board, z] :
         {std::pair{"shelf_bottom", panel / 2}, {"shelf_middle", height / 2}, {"shelf_top", height - panel / 2}}) {
      scene.obstacles.push_back(box(board, Vector3d(depth, width, panel), at(0, 0, z), yaw));
    }
    const auto ends = factory.straightLineEnds(a, b);
    if (!ends) continue;
    if (!factory.collisionFree(scene, *ends)) continue;
    setQuery(scene, *ends);
    return makeProblem(indexed(family.kind, index), family.kind, seed, index, std::move(scene));
  }
  throw Error(std::string("problem generator: no valid ") + family.kind + " problem " + std::to_string(index) +
              " for seed " + std::to_string(seed));
}

}  // namespace

std::vector<Problem> generateProblems(const GeneratorSettings& settings) {
  using Family = std::function<Problem(const ProblemFactory&, std::uint64_t, int)>;
  const auto furniture = [](Problem (*make)(const ProblemFactory&, std::uint64_t, int, const FurnitureFamily&),
                            const FurnitureFamily& family) -> Family {
    return [make, &family](const ProblemFactory& f, std::uint64_t seed, int i) { return make(f, seed, i, family); };
  };
  const std::vector<std::pair<int, Family>> families = {
      {settings.lineObstacles, lineObstacleProblem},
      {settings.pillars, furniture(pillarProblem, kPillars)},
      {settings.shelves, furniture(shelfProblem, kShelves)},
      {settings.clutter, clutterProblem},
      {settings.armBlocked, armBlockedProblem},
      {settings.walls, wallProblem},
      {settings.nearEndpoint, nearEndpointProblem},
      {settings.tallPillars, furniture(pillarProblem, kTallPillars)},
      {settings.deepShelves, furniture(shelfProblem, kDeepShelves)},
      {settings.forearmBeams, forearmBeamProblem},
      {settings.lintelGates, lintelGateProblem},
      {settings.tiltedTools, tiltedToolProblem},
  };
  for (const auto& [count, make] : families) {
    if (count < 0) throw Error("problem generator: problem counts must be >= 0");
  }
  const ProblemFactory factory;
  std::vector<Problem> problems;
  for (const auto& [count, make] : families) {
    for (int i = 0; i < count; ++i) problems.push_back(make(factory, settings.seed, i));
  }
  return problems;
}

}  // namespace arcplan::benchmarks
