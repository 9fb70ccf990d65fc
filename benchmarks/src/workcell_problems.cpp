// The workcell families of the generated suite: clutter, an obstacle only the arm hits, walls to pass
// over, obstacles close to the start or goal (problem_factory.h).
#include <functional>

#include "arcplan/common/error.h"
#include "problem_factory.h"

namespace arcplan::benchmarks::detail {
namespace {

// A random sphere, box or cylinder with its bounding radius between `low` and `high` (m), at `center`.
collision::Obstacle randomBody(Random& random, const std::string& name, double low, double high,
                               const Vector3d& center) {
  collision::Obstacle body;
  body.name = name;
  const double size = random.uniform(low, high);
  switch (random.choice(3)) {
    case 0:
      body.shape = collision::Obstacle::Shape::Sphere;
      body.radius = size;
      break;
    case 1:
      body.shape = collision::Obstacle::Shape::Box;
      body.size = Vector3d::Constant(2.0 * size / std::sqrt(3.0));
      break;
    default:
      body.shape = collision::Obstacle::Shape::Cylinder;
      body.radius = 0.5 * size;
      body.length = std::sqrt(3.0) * size;
      break;
  }
  body.pose.linear() = robot::rotationFromRpy(random.uniform(-M_PI, M_PI), random.uniform(-M_PI / 2, M_PI / 2), 0.0);
  body.pose.translation() = center;
  return body;
}

// A straight line that suits the workcell families: 0.55 - 1.0 m long, clear of the base axis.
std::optional<std::pair<Vector3d, Vector3d>> workcellLine(Random& random, double zLow, double zHigh) {
  const Vector3d a = workspacePoint(random, zLow, zHigh), b = workspacePoint(random, zLow, zHigh);
  const double length = (b - a).norm();
  if (length < 0.55 || length > 1.0 || distanceFromBaseAxis(a, b) < 0.4) return std::nullopt;
  return std::make_pair(a, b);
}

// Builds one problem of a workcell family: `place` adds the bodies for the line a-b (false: try again),
// `accept` judges the finished scene (default: any).
Problem workcellProblem(const ProblemFactory& factory, std::uint64_t seed, int index, const std::string& kind,
                        std::uint64_t stream, double zLow, double zHigh,
                        const std::function<bool(Random&, const Vector3d&, const Vector3d&, collision::Scene&)>& place,
                        const std::function<bool(const collision::Scene&, const Vector3d&, const Vector3d&,
                                                 const LineEnds&)>& accept = {}) {
  Random random(streamSeed(seed, stream, static_cast<std::uint64_t>(index)));
  for (int attempt = 0; attempt < kAttemptsPerProblem; ++attempt) {
    const auto line = workcellLine(random, zLow, zHigh);
    if (!line) continue;
    const auto& [a, b] = *line;
    auto scene = tableScene("");
    if (!place(random, a, b, scene)) continue;
    const auto ends = factory.straightLineEnds(a, b);
    if (!ends || !factory.collisionFree(scene, *ends)) continue;
    if (accept && !accept(scene, a, b, *ends)) continue;
    setQuery(scene, *ends);
    return makeProblem(indexed(kind, index), kind, seed, index, std::move(scene));
  }
  throw Error("problem generator: no valid " + kind + " problem " + std::to_string(index) + " for seed " +
              std::to_string(seed) + " after " + std::to_string(kAttemptsPerProblem) + " attempts");
}

bool aboveTable(const collision::Obstacle& body) { return body.boundingCenter().z() - body.boundingRadius() > 0.01; }

}  // namespace

// 2 - 5 small bodies scattered along and around the line.
Problem clutterProblem(const ProblemFactory& factory, std::uint64_t seed, int index) {
  return workcellProblem(factory, seed, index, "clutter", 4, 0.15, 0.5,
                         [](Random& random, const Vector3d& a, const Vector3d& b, collision::Scene& scene) {
                           const int count = 2 + random.choice(4);
                           for (int k = 0; k < count; ++k) {
                             const Vector3d center = a + random.uniform(0.2, 0.8) * (b - a) +
                                                     random.uniform(0.0, 0.12) * randomPerpendicular(random, b - a);
                             auto body = randomBody(random, "clutter_" + std::to_string(k), 0.02, 0.06, center);
                             if (!aboveTable(body) || (center - a).norm() < 0.12 || (center - b).norm() < 0.12)
                               return false;
                             scene.obstacles.push_back(body);
                           }
                           return true;
                         });
}

// A body above the middle of the line: the tool's line passes under it with room, the arm does not.
Problem armBlockedProblem(const ProblemFactory& factory, std::uint64_t seed, int index) {
  return workcellProblem(
      factory, seed, index, "arm-blocked", 5, 0.15, 0.4,
      [](Random& random, const Vector3d& a, const Vector3d& b, collision::Scene& scene) {
        const Vector3d center = a + random.uniform(0.35, 0.65) * (b - a) + Vector3d(0, 0, random.uniform(0.18, 0.4)) +
                                random.uniform(0.0, 0.08) * randomPerpendicular(random, b - a);
        scene.obstacles.push_back(randomBody(random, "overhead", 0.04, 0.09, center));
        return true;
      },
      [&factory](const collision::Scene& scene, const Vector3d& a, const Vector3d& b, const LineEnds& ends) {
        // The tool's line keeps 5 cm from the body (it is the arm that hits it).
        const collision::Obstacle& body = scene.obstacles.back();
        const Vector3d d = (b - a).normalized();
        const Vector3d nearest = a + std::clamp((body.boundingCenter() - a).dot(d), 0.0, (b - a).norm()) * d;
        return (nearest - body.boundingCenter()).norm() > body.boundingRadius() + 0.05 &&
               factory.lineCollides(scene, a, b, ends);
      });
}

// A thin wall standing on the table across the line, its top 5 - 20 cm above the line: pass over it.
Problem wallProblem(const ProblemFactory& factory, std::uint64_t seed, int index) {
  return workcellProblem(factory, seed, index, "wall", 6, 0.12, 0.3,
                         [](Random& random, const Vector3d& a, const Vector3d& b, collision::Scene& scene) {
                           const Vector3d middle = a + random.uniform(0.4, 0.6) * (b - a);
                           const double top = std::max(a.z(), b.z()) + random.uniform(0.05, 0.2);
                           const double yaw = std::atan2(b.y() - a.y(), b.x() - a.x());
                           const Vector3d size(random.uniform(0.02, 0.05), random.uniform(0.4, 0.8), top);
                           if (middle.head<2>().norm() < 0.5 * size.y() + 0.3) return false;  // clear of the base
                           scene.obstacles.push_back(box("wall", size, Vector3d(middle.x(), middle.y(), top / 2), yaw));
                           return true;
                         });
}

// A body on or beside the line 8 - 15 cm from the tool at the start or the goal.
Problem nearEndpointProblem(const ProblemFactory& factory, std::uint64_t seed, int index) {
  return workcellProblem(factory, seed, index, "near-end", 7, 0.15, 0.5,
                         [](Random& random, const Vector3d& a, const Vector3d& b, collision::Scene& scene) {
                           const bool atStart = random.choice(2) == 0;
                           const Vector3d end = atStart ? a : b, towards = (atStart ? b - a : a - b).normalized();
                           const Vector3d center = end + random.uniform(0.08, 0.15) * towards +
                                                   random.uniform(0.0, 0.05) * randomPerpendicular(random, towards);
                           auto body = randomBody(random, "near_end", 0.02, 0.05, center);
                           if (!aboveTable(body)) return false;
                           scene.obstacles.push_back(body);
                           return true;
                         });
}
}  // namespace arcplan::benchmarks::detail
