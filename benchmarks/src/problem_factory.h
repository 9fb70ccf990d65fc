#pragma once
// Internal to the problem generator (generated_problems.h): the seeded random numbers and the scene,
// line and naming helpers every family of generated problems shares. The line and furniture families
// are in generated_problems.cpp, the workcell families (clutter, arm-blocked, wall, near-end, and
// where the arm and not the tool meets a body: forearm-beam, lintel-gate, tilted-tool) in
// workcell_problems.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "arcplan/benchmarks/suite.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/common/error.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::benchmarks::detail {

using Eigen::Vector3d;
using robot::Vector6;

inline constexpr int kAttemptsPerProblem = 2000;
inline constexpr double kLineStep = 0.005;           // m, IK continuation step along the straight TCP line
inline constexpr double kMaxJointJumpPerStep = 0.1;  // rad: larger means the IK branch flipped
inline constexpr double kTableThickness = 0.05;
// Start and goal keep this much room (m): more than the built-in suites' 1 cm clearance, so that every
// planner's validity checker accepts them and a path can leave them.
inline constexpr double kEndpointClearance = 0.012;

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
inline std::uint64_t mix(std::uint64_t value) {
  value += 0x9e3779b97f4a7c15ULL;
  value = (value ^ (value >> 30)) * 0xbf58476d1ce4e5b9ULL;
  value = (value ^ (value >> 27)) * 0x94d049bb133111ebULL;
  return value ^ (value >> 31);
}

inline std::uint64_t streamSeed(std::uint64_t seed, std::uint64_t family, std::uint64_t index) {
  return mix(mix(mix(seed) ^ family) ^ index);
}

// The thesis' tool orientation: tool0 z pointing straight down.
inline Eigen::Matrix3d toolDown() { return robot::rotationFromRpy(0.0, -M_PI, M_PI / 2.0); }

// Elbow-up, wrist-down seed in the style of the thesis seeds, for a TCP at azimuth `azimuth`.
inline Vector6 thesisStyleSeed(double azimuth) {
  Vector6 seed;
  seed << azimuth - 0.3, -1.55, 2.2, -2.2, -M_PI / 2.0, azimuth - 0.3;
  return seed;
}

inline Eigen::Isometry3d toolPose(const Vector3d& position, const Eigen::Matrix3d& orientation = toolDown()) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = orientation;
  pose.translation() = position;
  return pose;
}

inline collision::Obstacle box(const std::string& name, const Vector3d& size, const Vector3d& center, double yaw) {
  collision::Obstacle obstacle;
  obstacle.name = name;
  obstacle.shape = collision::Obstacle::Shape::Box;
  obstacle.size = size;
  obstacle.pose = Eigen::Isometry3d::Identity();
  obstacle.pose.linear() = robot::rotationFromRpy(0.0, 0.0, yaw);
  obstacle.pose.translation() = center;
  return obstacle;
}

inline collision::Scene tableScene(const std::string& name) {
  collision::Scene scene;
  scene.name = name;
  scene.obstacles.push_back(
      box("table", Vector3d(2.0, 2.0, kTableThickness), Vector3d(0.0, 0.0, -kTableThickness / 2), 0.0));
  scene.allowedCollisions.emplace_back("table", "base_link_inertia");
  return scene;
}

// Checks and solves what every generated problem needs: start and goal poses (the tool held at one
// orientation) joined by a straight TCP line along which IK stays on one branch without jumps. The
// goal is where the continuation from the start arrives, so it lies on that branch; `path` is every
// configuration of that continuation, kLineStep of TCP travel apart, start and goal included.
struct LineEnds {
  Vector6 start;
  Vector6 goal;
  std::vector<Vector6> path;
};

class ProblemFactory {
public:
  ProblemFactory() : model_(robot::ur10e()), ik_(model_) {}

  const robot::RobotModel& model() const { return model_; }

  std::optional<LineEnds> straightLineEnds(const Vector3d& a, const Vector3d& b,
                                           const Eigen::Matrix3d& orientation = toolDown()) const {
    const auto start = ik_.solveNearest(toolPose(a, orientation), thesisStyleSeed(std::atan2(a.y(), a.x())));
    if (!start) return std::nullopt;
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / kLineStep)));
    std::vector<Vector6> path{*start};
    for (int k = 1; k <= steps; ++k) {
      const Vector3d point = a + (b - a) * (static_cast<double>(k) / steps);
      const auto next = ik_.solveNearest(toolPose(point, orientation), path.back());
      if (!next || (*next - path.back()).cwiseAbs().maxCoeff() > kMaxJointJumpPerStep) return std::nullopt;
      path.push_back(*next);
    }
    return LineEnds{*start, path.back(), std::move(path)};
  }

  static bool collisionFree(const collision::Scene& scene, const LineEnds& ends) {
    const auto model = collision::makeCollisionModel(scene);
    collision::CollisionData data(*model);
    return collision::distance(*model, data, ends.start).minimum() >= kEndpointClearance &&
           collision::distance(*model, data, ends.goal).minimum() >= kEndpointClearance;
  }

  // Whether the robot, following the straight TCP line from ends.start, touches a body of `scene` anywhere.
  static bool lineCollides(const collision::Scene& scene, const LineEnds& ends) {
    const auto model = collision::makeCollisionModel(scene);
    collision::CollisionData data(*model);
    return std::any_of(ends.path.begin() + 1, ends.path.end(),
                       [&](const Vector6& q) { return !collision::isCollisionFree(*model, data, q); });
  }

private:
  const robot::RobotModel& model_;
  robot::UrInverseKinematics ik_;
};

// The straight TCP line of the arm-contact families keeps this much room from every body (m): the
// built-in suites' clearance, so the tool itself could follow the line.
inline constexpr double kLineClearance = 0.01;

// Distance (m) from `point` to a sphere, box or cylinder (0 inside it).
inline double pointDistance(const collision::Obstacle& body, const Vector3d& point) {
  const Vector3d p = body.pose.inverse() * point;
  switch (body.shape) {
    case collision::Obstacle::Shape::Sphere:
      return std::max(p.norm() - body.radius, 0.0);
    case collision::Obstacle::Shape::Box:
      return (p.cwiseAbs() - 0.5 * body.size).cwiseMax(0.0).norm();
    case collision::Obstacle::Shape::Cylinder:
      return std::hypot(std::max(p.head<2>().norm() - body.radius, 0.0),
                        std::max(std::abs(p.z()) - 0.5 * body.length, 0.0));
    default:
      throw Error("problem generator: no point distance for the mesh obstacle '" + body.name + "'");
  }
}

// A lower bound of the distance (m) from the segment a-b to `body`: the smallest distance of points 1 mm
// apart, less half their spacing (a point's distance to a body changes no faster than the point moves).
inline double segmentDistance(const collision::Obstacle& body, const Vector3d& a, const Vector3d& b) {
  const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.001)));
  double nearest = pointDistance(body, a);
  for (int k = 1; k <= steps; ++k) nearest = std::min(nearest, pointDistance(body, a + (b - a) * (double(k) / steps)));
  return nearest - 0.5 * (b - a).norm() / steps;
}

// Per obstacle name, the robot links that touch it at some configuration of ends.path.
inline std::map<std::string, std::set<std::string>> contactsAlong(const collision::Scene& scene, const LineEnds& ends) {
  const auto model = collision::makeCollisionModel(scene);
  collision::CollisionData data(*model);
  std::map<std::string, std::set<std::string>> contacts;
  for (const auto& q : ends.path) {
    for (const auto& [link, body] : collision::collide(*model, data, q).collisions) contacts[body].insert(link);
  }
  return contacts;
}

// A random TCP point in front of and beside the robot, within comfortable reach.
inline Vector3d workspacePoint(Random& random, double zLow, double zHigh) {
  const double radius = random.uniform(0.4, 0.9);
  const double azimuth = random.uniform(-2.0, 2.0);
  return Vector3d(radius * std::cos(azimuth), radius * std::sin(azimuth), random.uniform(zLow, zHigh));
}

// Shortest horizontal distance from the robot's vertical axis to the segment a-b.
inline double distanceFromBaseAxis(const Vector3d& a, const Vector3d& b) {
  const Eigen::Vector2d p = a.head<2>(), d = (b - a).head<2>();
  const double t = d.squaredNorm() > 0 ? std::clamp(-p.dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p + t * d).norm();
}

// A unit vector orthogonal to `direction`, uniformly around it.
inline Vector3d randomPerpendicular(Random& random, const Vector3d& direction) {
  const Vector3d u = direction.unitOrthogonal();
  const Vector3d v = direction.normalized().cross(u);
  const double angle = random.uniform(-M_PI, M_PI);
  return std::cos(angle) * u + std::sin(angle) * v;
}

inline void setQuery(collision::Scene& scene, const LineEnds& ends) {
  collision::Query query;
  query.name = "main";
  query.start.joints = ends.start;
  query.goal.joints = ends.goal;
  scene.queries = {query};
}

inline std::string indexed(const std::string& family, int index) {
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "-%03d", index);
  return family + suffix;
}

inline Problem makeProblem(const std::string& name, const std::string& kind, std::uint64_t seed, int index,
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

// The workcell families (workcell_problems.cpp): problem `index` of each for `seed`. In the last three
// the straight TCP line keeps the clearance from every body while the arm following it does not.
Problem clutterProblem(const ProblemFactory& factory, std::uint64_t seed, int index);
Problem armBlockedProblem(const ProblemFactory& factory, std::uint64_t seed, int index);
Problem wallProblem(const ProblemFactory& factory, std::uint64_t seed, int index);
Problem nearEndpointProblem(const ProblemFactory& factory, std::uint64_t seed, int index);
Problem forearmBeamProblem(const ProblemFactory& factory, std::uint64_t seed, int index);
Problem lintelGateProblem(const ProblemFactory& factory, std::uint64_t seed, int index);
Problem tiltedToolProblem(const ProblemFactory& factory, std::uint64_t seed, int index);

}  // namespace arcplan::benchmarks::detail
