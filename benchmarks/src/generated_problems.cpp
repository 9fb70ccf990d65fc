#include "arcplan/benchmarks/generated_problems.h"

#include <cmath>
#include <cstdio>
#include <random>

#include <yaml-cpp/yaml.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/common/error.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::benchmarks {
namespace {

using robot::Vector6;
using Eigen::Vector3d;

constexpr int kAttemptsPerProblem = 2000;
constexpr double kLineStep = 0.005;          // m, IK continuation step along the straight TCP line
constexpr double kMaxJointJumpPerStep = 0.1;  // rad: larger means the IK branch flipped
constexpr double kTableThickness = 0.05;

// The standard fixes std::mt19937_64's output sequence but not the distributions built on it, so
// reals and choices are made here from the raw 64-bit output (identical on every platform).
class Random {
public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform(double low, double high) {
    const double unit = static_cast<double>(engine_() >> 11) * 0x1.0p-53;  // [0, 1) with 53 random bits
    return low + (high - low) * unit;
  }
  int choice(int count) { return static_cast<int>(engine_() % static_cast<std::uint64_t>(count)); }

private:
  std::mt19937_64 engine_;
};

// SplitMix64 finaliser: independent streams per (seed, family, index), so adding problems of one
// family leaves the others unchanged.
std::uint64_t mix(std::uint64_t value) {
  value += 0x9e3779b97f4a7c15ULL;
  value = (value ^ (value >> 30)) * 0xbf58476d1ce4e5b9ULL;
  value = (value ^ (value >> 27)) * 0x94d049bb133111ebULL;
  return value ^ (value >> 31);
}

std::uint64_t streamSeed(std::uint64_t seed, std::uint64_t family, std::uint64_t index) {
  return mix(mix(mix(seed) ^ family) ^ index);
}

// The thesis' tool orientation: tool0 z pointing straight down.
Eigen::Matrix3d toolDown() { return robot::rotationFromRpy(0.0, -M_PI, M_PI / 2.0); }

// Elbow-up, wrist-down seed in the style of the thesis seeds, for a TCP at azimuth `azimuth`.
Vector6 thesisStyleSeed(double azimuth) {
  Vector6 seed;
  seed << azimuth - 0.3, -1.55, 2.2, -2.2, -M_PI / 2.0, azimuth - 0.3;
  return seed;
}

Eigen::Isometry3d toolPose(const Vector3d& position) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = toolDown();
  pose.translation() = position;
  return pose;
}

collision::Obstacle box(const std::string& name, const Vector3d& size, const Vector3d& center, double yaw) {
  collision::Obstacle obstacle;
  obstacle.name = name;
  obstacle.shape = collision::Obstacle::Shape::Box;
  obstacle.size = size;
  obstacle.pose = Eigen::Isometry3d::Identity();
  obstacle.pose.linear() = robot::rotationFromRpy(0.0, 0.0, yaw);
  obstacle.pose.translation() = center;
  return obstacle;
}

collision::Scene tableScene(const std::string& name) {
  collision::Scene scene;
  scene.name = name;
  scene.obstacles.push_back(box("table", Vector3d(2.0, 2.0, kTableThickness), Vector3d(0.0, 0.0, -kTableThickness / 2), 0.0));
  scene.allowedCollisions.emplace_back("table", "base_link_inertia");
  return scene;
}

// Checks and solves what every generated problem needs: start and goal tool-down poses joined by a
// straight TCP line along which IK stays on one branch without jumps. Returns the joint vectors at
// A and B (the goal is where the continuation from the start arrives, so it lies on that branch).
struct LineEnds {
  Vector6 start;
  Vector6 goal;
};

class ProblemFactory {
public:
  ProblemFactory() : model_(robot::ur10e()), ik_(model_) {}

  std::optional<LineEnds> straightLineEnds(const Vector3d& a, const Vector3d& b) const {
    const auto start = ik_.solveNearest(toolPose(a), thesisStyleSeed(std::atan2(a.y(), a.x())));
    if (!start) return std::nullopt;
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / kLineStep)));
    Vector6 q = *start;
    for (int k = 1; k <= steps; ++k) {
      const Vector3d point = a + (b - a) * (static_cast<double>(k) / steps);
      const auto next = ik_.solveNearest(toolPose(point), q);
      if (!next || (*next - q).cwiseAbs().maxCoeff() > kMaxJointJumpPerStep) return std::nullopt;
      q = *next;
    }
    return LineEnds{*start, q};
  }

  static bool collisionFree(const collision::Scene& scene, const LineEnds& ends) {
    const auto model = collision::makeCollisionModel(scene);
    collision::CollisionData data(*model);
    return collision::isCollisionFree(*model, data, ends.start) && collision::isCollisionFree(*model, data, ends.goal);
  }

private:
  const robot::RobotModel& model_;
  robot::UrInverseKinematics ik_;
};

// A random TCP point in front of and beside the robot, within comfortable reach.
Vector3d workspacePoint(Random& random, double zLow, double zHigh) {
  const double radius = random.uniform(0.4, 0.9);
  const double azimuth = random.uniform(-2.0, 2.0);
  return Vector3d(radius * std::cos(azimuth), radius * std::sin(azimuth), random.uniform(zLow, zHigh));
}

// Shortest horizontal distance from the robot's vertical axis to the segment a-b.
double distanceFromBaseAxis(const Vector3d& a, const Vector3d& b) {
  const Eigen::Vector2d p = a.head<2>(), d = (b - a).head<2>();
  const double t = d.squaredNorm() > 0 ? std::clamp(-p.dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p + t * d).norm();
}

// A unit vector orthogonal to `direction`, uniformly around it.
Vector3d randomPerpendicular(Random& random, const Vector3d& direction) {
  const Vector3d u = direction.unitOrthogonal();
  const Vector3d v = direction.normalized().cross(u);
  const double angle = random.uniform(-M_PI, M_PI);
  return std::cos(angle) * u + std::sin(angle) * v;
}

void setQuery(collision::Scene& scene, const LineEnds& ends) {
  collision::Query query;
  query.name = "main";
  query.start.joints = ends.start;
  query.goal.joints = ends.goal;
  scene.queries = {query};
}

std::string indexed(const std::string& family, int index) {
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "-%03d", index);
  return family + suffix;
}

Problem makeProblem(const std::string& name, const std::string& kind, std::uint64_t seed, int index,
                    collision::Scene scene) {
  Problem problem;
  problem.name = name;
  problem.kind = kind;
  problem.origin = "generator seed " + std::to_string(seed) + ", " + kind + " problem " + std::to_string(index);
  scene.name = name;
  scene.sourceFile = problem.origin;
  problem.scene = std::move(scene);
  problem.query = "main";
  return problem;
}

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
    if (center.z() - bound < 0.01) continue;                                       // clear of the table
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

// A floor-to-ceiling column across the line: an arc of bounded height cannot clear it.
Problem pillarProblem(const ProblemFactory& factory, std::uint64_t seed, int index) {
  Random random(streamSeed(seed, 2, static_cast<std::uint64_t>(index)));
  for (int attempt = 0; attempt < kAttemptsPerProblem; ++attempt) {
    const Vector3d a = workspacePoint(random, 0.15, 0.5);
    const Vector3d b = workspacePoint(random, 0.15, 0.5);
    const double length = (b - a).norm();
    if (length < 0.6 || length > 1.1 || distanceFromBaseAxis(a, b) < 0.4) continue;
    const double radius = random.uniform(0.05, 0.09);
    const double height = 1.6;
    Vector3d center = a + random.uniform(0.4, 0.6) * (b - a);
    center += random.uniform(0.0, 0.5 * radius) * randomPerpendicular(random, Vector3d(b - a).cwiseProduct(Vector3d(1, 1, 0)));
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
    return makeProblem(indexed("pillar", index), "pillar", seed, index, std::move(scene));
  }
  throw Error("problem generator: no valid pillar problem " + std::to_string(index) + " for seed " + std::to_string(seed));
}

// A shelf unit (side panels, three boards, back panel facing the start) across the line: the tool
// has to go over or around a wall-like obstacle much larger than any arc detour.
Problem shelfProblem(const ProblemFactory& factory, std::uint64_t seed, int index) {
  Random random(streamSeed(seed, 3, static_cast<std::uint64_t>(index)));
  constexpr double panel = 0.02;
  for (int attempt = 0; attempt < kAttemptsPerProblem; ++attempt) {
    const Vector3d a = workspacePoint(random, 0.12, 0.3);
    const Vector3d b = workspacePoint(random, 0.12, 0.3);
    const double length = (b - a).head<2>().norm();
    if (length < 0.65 || length > 1.1 || distanceFromBaseAxis(a, b) < 0.45) continue;
    const double width = random.uniform(0.4, 0.6), depth = random.uniform(0.25, 0.35), height = random.uniform(0.55, 0.8);
    const Vector3d middle = 0.5 * (a + b);
    const double yaw = std::atan2(b.y() - a.y(), b.x() - a.x());  // shelf x axis along the line's projection
    if (middle.head<2>().norm() < 0.5 * std::hypot(width, depth) + 0.25) continue;

    const Eigen::Matrix3d rotation = robot::rotationFromRpy(0.0, 0.0, yaw);
    const auto at = [&](double x, double y, double z) -> Vector3d {
      return Vector3d(middle.x(), middle.y(), 0.0) + rotation * Vector3d(x, y, z);
    };
    auto scene = tableScene("");
    scene.obstacles.push_back(box("shelf_back", Vector3d(panel, width, height), at(depth / 2 - panel / 2, 0, height / 2), yaw));
    scene.obstacles.push_back(box("shelf_left", Vector3d(depth, panel, height), at(0, width / 2 - panel / 2, height / 2), yaw));
    scene.obstacles.push_back(box("shelf_right", Vector3d(depth, panel, height), at(0, -width / 2 + panel / 2, height / 2), yaw));
    for (const auto& [board, z] : {std::pair{"shelf_bottom", panel / 2}, {"shelf_middle", height / 2}, {"shelf_top", height - panel / 2}}) {
      scene.obstacles.push_back(box(board, Vector3d(depth, width, panel), at(0, 0, z), yaw));
    }
    const auto ends = factory.straightLineEnds(a, b);
    if (!ends) continue;
    if (!factory.collisionFree(scene, *ends)) continue;
    setQuery(scene, *ends);
    return makeProblem(indexed("shelf", index), "shelf", seed, index, std::move(scene));
  }
  throw Error("problem generator: no valid shelf problem " + std::to_string(index) + " for seed " + std::to_string(seed));
}

void emitVector(YAML::Emitter& out, const double* values, int count) {
  out << YAML::Flow << YAML::BeginSeq;
  for (int i = 0; i < count; ++i) out << values[i] + 0.0;  // + 0.0 writes -0 as 0
  out << YAML::EndSeq;
}

}  // namespace

std::vector<Problem> generateProblems(const GeneratorSettings& settings) {
  if (settings.lineObstacles < 0 || settings.pillars < 0 || settings.shelves < 0) {
    throw Error("problem generator: problem counts must be >= 0");
  }
  const ProblemFactory factory;
  std::vector<Problem> problems;
  for (int i = 0; i < settings.lineObstacles; ++i) problems.push_back(lineObstacleProblem(factory, settings.seed, i));
  for (int i = 0; i < settings.pillars; ++i) problems.push_back(pillarProblem(factory, settings.seed, i));
  for (int i = 0; i < settings.shelves; ++i) problems.push_back(shelfProblem(factory, settings.seed, i));
  return problems;
}

std::string sceneToYaml(const collision::Scene& scene) {
  YAML::Emitter out;
  out.SetDoublePrecision(15);  // readable (0.05, not 0.050000000000000003) and within 1e-15 of the value
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << scene.name;
  out << YAML::Key << "robot" << YAML::Value;
  if (scene.robotUrdf.empty()) {
    out << "ur10e";
  } else {
    out << YAML::BeginMap << YAML::Key << "urdf" << YAML::Value << scene.robotUrdf.string() << YAML::EndMap;
  }
  out << YAML::Key << "obstacles" << YAML::Value << YAML::BeginSeq;
  for (const auto& obstacle : scene.obstacles) {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << obstacle.name;
    switch (obstacle.shape) {
      case collision::Obstacle::Shape::Sphere:
        out << YAML::Key << "sphere" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "radius"
            << YAML::Value << obstacle.radius << YAML::EndMap;
        break;
      case collision::Obstacle::Shape::Box:
        out << YAML::Key << "box" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "size" << YAML::Value;
        emitVector(out, obstacle.size.data(), 3);
        out << YAML::EndMap;
        break;
      case collision::Obstacle::Shape::Cylinder:
        out << YAML::Key << "cylinder" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "radius"
            << YAML::Value << obstacle.radius << YAML::Key << "length" << YAML::Value << obstacle.length << YAML::EndMap;
        break;
      case collision::Obstacle::Shape::Mesh: {
        out << YAML::Key << "mesh" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "file" << YAML::Value
            << obstacle.meshFile.string() << YAML::Key << "scale" << YAML::Value;
        emitVector(out, obstacle.meshScale.data(), 3);
        out << YAML::EndMap;
        break;
      }
    }
    const Vector3d position = obstacle.pose.translation();
    const Vector3d rpy = robot::rpyFromRotation(obstacle.pose.linear());
    out << YAML::Key << "position" << YAML::Value;
    emitVector(out, position.data(), 3);
    out << YAML::Key << "rpy" << YAML::Value;
    emitVector(out, rpy.data(), 3);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  if (!scene.allowedCollisions.empty()) {
    out << YAML::Key << "allowed_collisions" << YAML::Value << YAML::BeginSeq;
    for (const auto& [first, second] : scene.allowedCollisions) {
      out << YAML::Flow << YAML::BeginSeq << first << second << YAML::EndSeq;
    }
    out << YAML::EndSeq;
  }
  out << YAML::Key << "queries" << YAML::Value << YAML::BeginSeq;
  for (const auto& query : scene.queries) {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << query.name;
    for (const auto& [key, endpoint] : {std::pair{"start", &query.start}, {"goal", &query.goal}}) {
      out << YAML::Key << key << YAML::Value << YAML::BeginMap;
      if (endpoint->joints) {
        out << YAML::Key << "joints" << YAML::Value;
        emitVector(out, endpoint->joints->data(), 6);
      } else if (endpoint->pose) {
        out << YAML::Key << "pose" << YAML::Value;
        emitVector(out, endpoint->pose->data(), 6);
        if (endpoint->seed) {
          out << YAML::Key << "seed" << YAML::Value;
          emitVector(out, endpoint->seed->data(), 6);
        }
      }
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace arcplan::benchmarks
