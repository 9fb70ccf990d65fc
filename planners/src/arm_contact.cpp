#include "arm_contact.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <unordered_map>

#include "arcplan/common/error.h"
#include "arcplan/planners/arc_path.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/mesh.h"

namespace arcplan::planners {
namespace {

using robot::CollisionGeometry;

// Outline points of one collision element, in its link's frame.
std::vector<Eigen::Vector3d> outlineOf(const CollisionGeometry& geometry) {
  std::vector<Eigen::Vector3d> local;
  switch (geometry.shape) {
    case CollisionGeometry::Shape::Mesh: {
      const std::vector<Eigen::Vector3d> vertices = robot::loadMesh(geometry.meshFile, geometry.meshScale).vertices;
      const std::size_t stride = std::max<std::size_t>(1, vertices.size() / kOutlinePoints);
      for (std::size_t i = 0; i < vertices.size(); i += stride) local.push_back(vertices[i]);
      break;
    }
    case CollisionGeometry::Shape::Box:
      for (int corner = 0; corner < 8; ++corner) {
        local.emplace_back(Eigen::Vector3d(corner & 1 ? 0.5 : -0.5, corner & 2 ? 0.5 : -0.5, corner & 4 ? 0.5 : -0.5)
                               .cwiseProduct(geometry.boxSize));
      }
      break;
    case CollisionGeometry::Shape::Cylinder:
      for (int k = 0; k < 16; ++k) {
        const double angle = M_PI * k / 4.0;  // two end circles, 8 points each
        local.emplace_back(geometry.radius * std::cos(angle), geometry.radius * std::sin(angle),
                           (k < 8 ? -0.5 : 0.5) * geometry.length);
      }
      break;
    case CollisionGeometry::Shape::Sphere:
      local.emplace_back(Eigen::Vector3d::Zero());
      break;
  }
  for (Eigen::Vector3d& p : local) p = geometry.origin * p;
  return local;
}

double distanceToBox(const Eigen::Vector3d& p, const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  return (low - p).cwiseMax(p - high).cwiseMax(0.0).norm();
}

// The outline point of `link` (world frame) nearest the body (nearest its hull's bounding box first,
// 0 for every point inside it, then nearest its centre) and the side of the body it is on.
ArmContact nearestPoint(const Eigen::Isometry3d& linkPose, const std::vector<Eigen::Vector3d>& outline,
                        const collision::Obstacle& body) {
  const std::vector<Eigen::Vector3d> hull = hullPoints(body);
  Eigen::Vector3d low = hull.front(), high = hull.front();
  for (const Eigen::Vector3d& p : hull) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const Eigen::Vector3d centre = 0.5 * (low + high);
  Eigen::Vector3d best = linkPose.translation();
  double bestScore = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& local : outline) {
    const Eigen::Vector3d p = linkPose * local;
    const double score = distanceToBox(p, low, high) + 1e-3 * (p - centre).norm();
    if (score < bestScore) {
      bestScore = score;
      best = p;
    }
  }
  ArmContact contact;
  contact.offset = best;  // the caller makes it relative to the TCP
  const Eigen::Vector3d outward = best - best.cwiseMax(low).cwiseMin(high);
  contact.side = (outward.norm() > 1e-6 ? outward : Eigen::Vector3d(best - centre)).normalized();
  return contact;
}

}  // namespace

LinkOutlines linkOutlines(const robot::RobotModel& robot) {
  LinkOutlines outlines;
  for (const robot::Link& link : robot.links()) {
    std::vector<Eigen::Vector3d> points;
    for (const CollisionGeometry& geometry : link.collisions) {
      try {
        const std::vector<Eigen::Vector3d> more = outlineOf(geometry);
        points.insert(points.end(), more.begin(), more.end());
      } catch (const Error&) {
        // An unreadable mesh leaves the link its origin (the collision model reports the file itself).
      }
    }
    if (points.empty()) points.emplace_back(Eigen::Vector3d::Zero());
    outlines.push_back(std::move(points));
  }
  return outlines;
}

std::vector<ArmContact> armContacts(const robot::RobotModel& robot, const LinkOutlines& outlines,
                                    const robot::Vector6& q,
                                    const std::vector<std::pair<std::string, std::string>>& pairs,
                                    const std::vector<collision::Obstacle>& bodies) {
  robot::KinematicsData kinematics(robot);
  robot::forwardKinematics(robot, q, kinematics);
  const Eigen::Vector3d tcp = kinematics.linkPoses[static_cast<std::size_t>(robot.tipLink())].translation();
  std::vector<ArmContact> contacts;
  for (const auto& [linkName, bodyName] : pairs) {
    const auto link = std::find_if(robot.links().begin(), robot.links().end(),
                                   [&](const robot::Link& l) { return l.name == linkName; });
    const auto body =
        std::find_if(bodies.begin(), bodies.end(), [&](const collision::Obstacle& b) { return b.name == bodyName; });
    if (link == robot.links().end() || body == bodies.end()) continue;
    if (std::any_of(contacts.begin(), contacts.end(), [&](const ArmContact& c) { return c.link == linkName; }))
      continue;
    const auto index = static_cast<std::size_t>(link - robot.links().begin());
    ArmContact contact = nearestPoint(kinematics.linkPoses[index], outlines.at(index), *body);
    contact.link = linkName;
    contact.offset -= tcp;
    for (const Eigen::Vector3d& local : outlines.at(index))
      contact.outline.push_back(kinematics.linkPoses[index] * local - tcp);
    if (contact.offset.norm() > kArmContactReach) contacts.push_back(std::move(contact));
  }
  return contacts;
}

ObstacleCluster seenFromTheTcp(const ObstacleCluster& cluster, const std::vector<Eigen::Vector3d>& link) {
  ObstacleCluster shifted = cluster;
  shifted.hull.clear();
  for (const Eigen::Vector3d& h : cluster.hull) {
    for (const Eigen::Vector3d& l : link) shifted.hull.push_back(h - l);
  }
  return shifted;
}

BlockedSpan blockedSpan(const Eigen::Vector3d& p, const Eigen::Vector3d& q, double at, const PostureClear& clear) {
  const double length = (q - p).norm();
  const Eigen::Vector3d along = (q - p) / length;
  BlockedSpan span{at, at};
  if (clear(p + at * along)) return span;
  while (span.from > 0.0 && !clear(p + std::max(span.from - kPostureProbeStep, 0.0) * along))
    span.from = std::max(span.from - kPostureProbeStep, 0.0);
  while (span.to < length && !clear(p + std::min(span.to + kPostureProbeStep, length) * along))
    span.to = std::min(span.to + kPostureProbeStep, length);
  return span;
}

namespace {

constexpr int kDetourPlanes = 12;        // 30° apart, as viaCandidates
constexpr double kDetourEndKeep = 0.01;  // m along the leg from p and q

// Every posture probed along a -> b (a itself excluded, b included) is clear.
bool segmentClear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const PostureClear& clear) {
  const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / kPostureProbeStep)));
  for (int k = 1; k <= steps; ++k) {
    if (!clear(a + (b - a) * (static_cast<double>(k) / steps))) return false;
  }
  return true;
}

}  // namespace

std::vector<ViaCandidate> clearingDetours(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const BlockedSpan& span,
                                          const PostureClear& clear) {
  std::vector<ViaCandidate> detours;
  const double length = (q - p).norm();
  if (length < 4.0 * kDetourEndKeep) return detours;
  const Eigen::Vector3d along = (q - p) / length;
  const auto inside = [&](double x) { return std::clamp(x, kDetourEndKeep, length - kDetourEndKeep); };
  for (int plane = 0; plane < kDetourPlanes; ++plane) {
    const Eigen::Vector3d away = avoidanceDirection(along, 2.0 * M_PI * plane / kDetourPlanes);
    double below = 0.0;
    for (const double lift : kDetourLifts) {
      const Eigen::Vector3d enter = p + inside(span.from - lift) * along + lift * away;
      const Eigen::Vector3d leave = p + inside(span.to + lift) * along + lift * away;
      const bool clears = clear(enter) && segmentClear(enter, leave, clear) && segmentClear(p, enter, clear) &&
                          segmentClear(leave, q, clear);
      if (clears) {
        ViaCandidate detour{{enter}, lift - below};
        if ((leave - enter).norm() > 1e-3) detour.points.push_back(leave);
        detours.push_back(std::move(detour));
        break;
      }
      below = lift;
    }
  }
  return detours;
}

namespace {

// A lattice point, i, j, k steps from the origin, packed into one key (|i|, |j|, |k| < 2^20).
std::int64_t latticeKey(const Eigen::Vector3i& cell) {
  constexpr std::int64_t kSpan = 1 << 21, kHalf = 1 << 20;
  return ((cell.x() + kHalf) * kSpan + (cell.y() + kHalf)) * kSpan + (cell.z() + kHalf);
}

// The lattice path p -> ... -> q, or nothing when none was found within kLatticeTests tests.
std::optional<std::vector<Eigen::Vector3d>> latticePath(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                                        const PostureClear& clear) {
  // One record per cell met, its test and its search node together: one hash lookup per neighbour (a map for each
  // was a fifth of the lattice's time, most of it walking the two maps' buckets).
  constexpr double kUnreached = std::numeric_limits<double>::infinity();
  struct Cell {
    Eigen::Vector3i cell;
    enum class Test : std::int8_t { Unknown, Clear, Blocked } test = Test::Unknown;
    double cost = kUnreached;  // from p, once reached
    std::int64_t parent = -1;
    bool closed = false;
  };
  std::unordered_map<std::int64_t, Cell> cells;
  cells.reserve(4 * 1024);
  using Entry = std::pair<double, std::int64_t>;  // cost + heuristic, key
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  const auto position = [&](const Eigen::Vector3i& cell) -> Eigen::Vector3d {
    return p + kLatticeStep * cell.cast<double>();
  };
  cells[latticeKey(Eigen::Vector3i::Zero())] = Cell{Eigen::Vector3i::Zero(), Cell::Test::Clear, 0.0, -1, false};
  open.emplace((q - p).norm(), latticeKey(Eigen::Vector3i::Zero()));
  int tests = 0;
  while (!open.empty()) {
    const std::int64_t key = open.top().second;
    open.pop();
    Cell& node = cells.at(key);
    if (node.closed) continue;
    node.closed = true;
    const Eigen::Vector3d here = position(node.cell);
    // A cell is tested when it is taken, not when it is met (lazily): a cell's test decides only whether it is
    // expanded, and a blocked cell never is, so the cells expanded, their parents and the path found are those of
    // testing every neighbour as it is met, for a fraction of the tests (each expansion meets up to 26 cells, most
    // never taken).
    if (node.test == Cell::Test::Unknown) {
      if (++tests > kLatticeTests) return std::nullopt;
      node.test = clear(here) ? Cell::Test::Clear : Cell::Test::Blocked;
    }
    if (node.test == Cell::Test::Blocked) continue;
    if ((q - here).norm() < 2.0 * kLatticeStep && segmentClear(here, q, clear)) {
      std::vector<Eigen::Vector3d> path{q};
      for (std::int64_t k = key; k != -1; k = cells.at(k).parent) path.push_back(position(cells.at(k).cell));
      path.back() = p;
      std::reverse(path.begin(), path.end());
      return path;
    }
    const Cell from = node;  // cells may rehash below
    for (int n = 0; n < 27; ++n) {
      const Eigen::Vector3i step(n % 3 - 1, n / 3 % 3 - 1, n / 9 - 1);
      if (step.isZero()) continue;
      const Eigen::Vector3i cell = from.cell + step;
      const std::int64_t next = latticeKey(cell);
      Cell& neighbour = cells.try_emplace(next, Cell{cell}).first->second;
      if (neighbour.test == Cell::Test::Blocked) continue;
      const double cost = from.cost + kLatticeStep * step.cast<double>().norm();
      if (neighbour.closed || neighbour.cost <= cost) continue;
      neighbour.cost = cost;
      neighbour.parent = key;
      open.emplace(cost + kLatticeGreed * (q - position(cell)).norm(), next);
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<ViaCandidate> latticeDetour(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const PostureClear& clear,
                                          std::size_t maxViaPoints) {
  const std::optional<std::vector<Eigen::Vector3d>> path = latticePath(p, q, clear);
  if (!path) return std::nullopt;
  // Greedy: from each kept point, the farthest later point the straight leg reaches clear.
  ViaCandidate detour{{}, kLatticeStep};
  std::size_t from = 0;
  while (from + 1 < path->size()) {
    std::size_t to = path->size() - 1;
    while (to > from + 1 && !segmentClear((*path)[from], (*path)[to], clear)) --to;
    if (to + 1 < path->size()) detour.points.push_back((*path)[to]);
    if (detour.points.size() > maxViaPoints) return std::nullopt;
    from = to;
  }
  if (detour.points.empty()) return std::nullopt;  // the straight leg is clear: nothing to detour
  return detour;
}

}  // namespace arcplan::planners
