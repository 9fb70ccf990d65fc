// The workcell families of the generated suite: clutter, an obstacle only the arm hits, walls to pass
// over, obstacles close to the start or goal; and where the straight TCP line is free but the arm
// following it is not: beams across the forearm's sweep, gates with a low lintel, tilted tools
// (problem_factory.h).
#include <functional>

#include "arcplan/robot/kinematics.h"

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
      [](const collision::Scene& scene, const Vector3d& a, const Vector3d& b, const LineEnds& ends) {
        // The tool's line keeps 5 cm from the body (it is the arm that hits it).
        const collision::Obstacle& body = scene.obstacles.back();
        const Vector3d d = (b - a).normalized();
        const Vector3d nearest = a + std::clamp((body.boundingCenter() - a).dot(d), 0.0, (b - a).norm()) * d;
        return (nearest - body.boundingCenter()).norm() > body.boundingRadius() + 0.05 &&
               ProblemFactory::lineCollides(scene, ends);
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

namespace {

// Adds the bodies of one arm-contact problem for the straight line a-b and its IK path; returns the
// name of the body the arm must meet, or nothing to draw again.
using ArmContactPlacement = std::function<std::optional<std::string>(
    Random&, const ProblemFactory&, const Vector3d&, const Vector3d&, const LineEnds&, collision::Scene&)>;

// A family where the arm, not the tool, is blocked: the straight TCP line keeps kLineClearance from every
// body, while one of `arm` (robot links) touches the blocking body somewhere along that line's IK path
// (every kLineStep) and the tool's link (wrist_3_link, which tool0 is fixed to) touches no body unless
// it is one of `arm`.
struct ArmContactFamily {
  const char* kind;
  std::uint64_t stream;
  double zLow, zHigh;  // height range of the line's ends (m)
  std::set<std::string> arm;
  bool tiltedTool;  // the tool held 30-70 degrees off straight down (else straight down)
};

const char* const kToolLink = "wrist_3_link";

// The tool's z axis tilted 30-70 degrees from straight down, towards a random azimuth.
Eigen::Matrix3d tiltedTool(Random& random) {
  const double tilt = random.uniform(M_PI / 6.0, 7.0 * M_PI / 18.0), azimuth = random.uniform(-M_PI, M_PI);
  return Eigen::AngleAxisd(tilt, Vector3d(-std::sin(azimuth), std::cos(azimuth), 0.0)).toRotationMatrix() * toolDown();
}

bool armMeetsTheBody(const ArmContactFamily& family, const collision::Scene& scene, const Vector3d& a,
                     const Vector3d& b, const LineEnds& ends, const std::string& blocking) {
  for (std::size_t i = 1; i < scene.obstacles.size(); ++i) {  // the table (first) is below the line
    if (segmentDistance(scene.obstacles[i], a, b) < kLineClearance) return false;
  }
  const auto contacts = contactsAlong(scene, ends);
  const bool toolTouches =
      std::any_of(contacts.begin(), contacts.end(), [](const auto& body) { return body.second.count(kToolLink) > 0; });
  if (toolTouches && family.arm.count(kToolLink) == 0) return false;
  const auto blocked = contacts.find(blocking);
  return blocked != contacts.end() && std::any_of(family.arm.begin(), family.arm.end(), [&](const std::string& link) {
           return blocked->second.count(link) > 0;
         });
}

Problem armContactProblem(const ProblemFactory& factory, std::uint64_t seed, int index, const ArmContactFamily& family,
                          const ArmContactPlacement& place) {
  Random random(streamSeed(seed, family.stream, static_cast<std::uint64_t>(index)));
  for (int attempt = 0; attempt < kAttemptsPerProblem; ++attempt) {
    const Eigen::Matrix3d orientation = family.tiltedTool ? tiltedTool(random) : toolDown();
    const auto line = workcellLine(random, family.zLow, family.zHigh);
    if (!line) continue;
    const auto& [a, b] = *line;
    const auto ends = factory.straightLineEnds(a, b, orientation);
    if (!ends) continue;
    auto scene = tableScene("");
    const auto blocking = place(random, factory, a, b, *ends, scene);
    if (!blocking || !factory.collisionFree(scene, *ends)) continue;
    if (!armMeetsTheBody(family, scene, a, b, *ends, *blocking)) continue;
    setQuery(scene, *ends);
    return makeProblem(indexed(family.kind, index), family.kind, seed, index, std::move(scene));
  }
  throw Error(std::string("problem generator: no valid ") + family.kind + " problem " + std::to_string(index) +
              " for seed " + std::to_string(seed) + " after " + std::to_string(kAttemptsPerProblem) +
              " attempts (the straight TCP line must keep 1 cm from every body while the arm following it "
              "touches the blocking one)");
}

// Where link `link` is at configuration `i` of the path (its frame's origin).
Vector3d linkOrigin(const ProblemFactory& factory, const LineEnds& ends, std::size_t i, const std::string& link) {
  robot::KinematicsData kinematics(factory.model());
  robot::forwardKinematics(factory.model(), ends.path[i], kinematics);
  return kinematics.linkPoses[static_cast<std::size_t>(factory.model().linkIndex(link))].translation();
}

// A configuration of the middle 30-70 % of the path.
std::size_t middleOfPath(Random& random, const LineEnds& ends) {
  const auto last = static_cast<double>(ends.path.size() - 1);
  return static_cast<std::size_t>(std::lround(random.uniform(0.3, 0.7) * last));
}

const ArmContactFamily kForearmBeams{"forearm-beam", 10, 0.12, 0.45, {"upper_arm_link", "forearm_link"}, false};
const ArmContactFamily kLintelGates{"lintel-gate", 11, 0.12, 0.35, {"forearm_link", "wrist_1_link", "wrist_2_link"},
                                    false};
const ArmContactFamily kTiltedTools{"tilted-tool", 12, 0.2, 0.55, {"wrist_1_link", "wrist_2_link", kToolLink}, true};

}  // namespace

// A horizontal beam (0.5-1.2 m long, 4-12 cm thick) through a point of the forearm (elbow to wrist 1)
// in the middle of the path, across the direction that point moves: the elbow sweeps into it.
Problem forearmBeamProblem(const ProblemFactory& factory, std::uint64_t seed, int index) {
  return armContactProblem(
      factory, seed, index, kForearmBeams,
      [](Random& random, const ProblemFactory& f, const Vector3d&, const Vector3d&, const LineEnds& ends,
         collision::Scene& scene) -> std::optional<std::string> {
        const std::size_t k = middleOfPath(random, ends), last = ends.path.size() - 1;
        const double s = random.uniform(0.0, 0.9);
        const auto forearmPoint = [&](std::size_t i) -> Vector3d {
          const Vector3d elbow = linkOrigin(f, ends, i, "forearm_link");
          return elbow + s * (linkOrigin(f, ends, i, "wrist_1_link") - elbow);
        };
        const Vector3d sweep = forearmPoint(std::min(k + 5, last)) - forearmPoint(k < 5 ? 0 : k - 5);
        double yaw = random.uniform(-0.6, 0.6);
        yaw +=
            sweep.head<2>().norm() > 1e-3 ? std::atan2(sweep.y(), sweep.x()) + M_PI / 2.0 : random.uniform(-M_PI, M_PI);
        const Vector3d size(random.uniform(0.5, 1.2), random.uniform(0.04, 0.12), random.uniform(0.04, 0.12));
        const Vector3d center = forearmPoint(k) +
                                random.uniform(-0.3, 0.3) * size.x() * Vector3d(std::cos(yaw), std::sin(yaw), 0.0) +
                                Vector3d(0.0, 0.0, random.uniform(-1.0, 1.0) * (0.5 * size.z() + 0.04));
        if (center.z() - 0.5 * size.z() < 0.02) return std::nullopt;  // above the table
        scene.obstacles.push_back(box("beam", size, center, yaw));
        return "beam";
      });
}

// A gate across the middle of the line (two posts on the table, 0.25-0.6 m apart, and a lintel 5-35 cm
// above the line): the tool passes through, the forearm or wrist above it meets the lintel.
Problem lintelGateProblem(const ProblemFactory& factory, std::uint64_t seed, int index) {
  return armContactProblem(
      factory, seed, index, kLintelGates,
      [](Random& random, const ProblemFactory&, const Vector3d& a, const Vector3d& b, const LineEnds&,
         collision::Scene& scene) -> std::optional<std::string> {
        const Vector3d middle = a + random.uniform(0.35, 0.65) * (b - a);
        const double yaw = std::atan2(b.y() - a.y(), b.x() - a.x());  // gate x axis along the line
        const double width = random.uniform(0.25, 0.6), post = random.uniform(0.04, 0.08);
        const double bottom = middle.z() + random.uniform(0.05, 0.35), thickness = random.uniform(0.04, 0.1);
        const double depth = random.uniform(0.04, 0.15);
        const Eigen::Matrix3d rotation = robot::rotationFromRpy(0.0, 0.0, yaw);
        const Vector3d center =
            Vector3d(middle.x(), middle.y(), 0.0) + rotation * Vector3d(0.0, random.uniform(-0.2, 0.2) * width, 0.0);
        for (const double side : {1.0, -1.0}) {
          scene.obstacles.push_back(box(side > 0 ? "gate_left" : "gate_right", Vector3d(post, post, bottom),
                                        center + rotation * Vector3d(0.0, side * 0.5 * (width + post), 0.5 * bottom),
                                        yaw));
        }
        scene.obstacles.push_back(box("lintel", Vector3d(depth, width + 2.0 * post, thickness),
                                      center + Vector3d(0.0, 0.0, bottom + 0.5 * thickness), yaw));
        return "lintel";
      });
}

// The tool held 30-70 degrees off straight down, and a small body (bounding radius 3-8 cm) where the
// wrist (tool0 to wrist 2) passes in the middle of the path, beside the line the TCP follows.
Problem tiltedToolProblem(const ProblemFactory& factory, std::uint64_t seed, int index) {
  return armContactProblem(factory, seed, index, kTiltedTools,
                           [](Random& random, const ProblemFactory& f, const Vector3d& a, const Vector3d& b,
                              const LineEnds& ends, collision::Scene& scene) -> std::optional<std::string> {
                             const std::size_t k = middleOfPath(random, ends);
                             const Vector3d tcp = linkOrigin(f, ends, k, "tool0");
                             const Vector3d wrist = linkOrigin(f, ends, k, "wrist_2_link");
                             const Vector3d center = tcp + random.uniform(0.4, 1.4) * (wrist - tcp) +
                                                     random.uniform(0.0, 0.05) * randomPerpendicular(random, b - a);
                             auto body = randomBody(random, "obstacle", 0.03, 0.08, center);
                             if (!aboveTable(body)) return std::nullopt;
                             scene.obstacles.push_back(body);
                             return "obstacle";
                           });
}
}  // namespace arcplan::benchmarks::detail
