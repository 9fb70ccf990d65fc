#include "via_points.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "arcplan/planners/arc_path.h"

namespace arcplan::planners {
namespace {

// Margins beyond the clearance (m): the tool flange is ~5 cm in radius, the wrist links above it
// reach ~15 cm further; the largest lets the forearm pass over low walls.
const double kMargins[] = {0.02, 0.05, 0.1, 0.2, 0.35};
constexpr int kPlaneSteps = 12;       // 30° apart
constexpr double kEndKeepOut = 0.01;  // m along the leg from p and q
constexpr double kHighestApex = 1.5;  // m above the leg
constexpr double kFloorTop = 0.01;    // m: a body whose top is this low is the floor the robot stands on
const double kWithinSide = std::cos(M_PI / 3.0 + 1e-9);  // planes within 60° of a given side (5 of 12)

struct Box {
  Eigen::Vector3d low, high;
};

Box boundsOf(const std::vector<Eigen::Vector3d>& points) {
  Box box{points.front(), points.front()};
  for (const Eigen::Vector3d& p : points) {
    box.low = box.low.cwiseMin(p);
    box.high = box.high.cwiseMax(p);
  }
  return box;
}

bool near(const Box& a, const Box& b, double gap) {
  return ((a.low.array() - gap) <= b.high.array()).all() && ((b.low.array() - gap) <= a.high.array()).all();
}

}  // namespace

std::vector<Eigen::Vector3d> hullPoints(const collision::Obstacle& obstacle) {
  std::vector<Eigen::Vector3d> local;
  using Shape = collision::Obstacle::Shape;
  if (obstacle.shape == Shape::Box) {
    for (int corner = 0; corner < 8; ++corner) {
      local.emplace_back((corner & 1 ? 0.5 : -0.5) * obstacle.size.x(), (corner & 2 ? 0.5 : -0.5) * obstacle.size.y(),
                         (corner & 4 ? 0.5 : -0.5) * obstacle.size.z());
    }
  } else if (obstacle.shape == Shape::Cylinder) {
    const double circumscribed = obstacle.radius / std::cos(M_PI / 8.0);  // octagon around the circle
    for (const double z : {-0.5 * obstacle.length, 0.5 * obstacle.length}) {
      for (int k = 0; k < 8; ++k) {
        const double angle = M_PI / 8.0 + k * M_PI / 4.0;
        local.emplace_back(circumscribed * std::cos(angle), circumscribed * std::sin(angle), z);
      }
    }
  }
  if (local.empty()) {  // sphere or mesh: the cube around its bounding ball
    const double r = obstacle.boundingRadius();
    std::vector<Eigen::Vector3d> cube;
    for (int corner = 0; corner < 8; ++corner) {
      cube.push_back(obstacle.boundingCenter() +
                     r * Eigen::Vector3d(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1));
    }
    return cube;
  }
  std::vector<Eigen::Vector3d> world;
  for (const Eigen::Vector3d& p : local) world.push_back(obstacle.pose * p);
  return world;
}

std::vector<ObstacleCluster> clusterObstacles(const std::vector<collision::Obstacle>& obstacles, double gap) {
  std::vector<ObstacleCluster> clusters;
  std::vector<Box> bounds;  // per body of `members`
  std::vector<std::size_t> clusterOf;
  std::vector<std::vector<Eigen::Vector3d>> hulls;
  for (const collision::Obstacle& obstacle : obstacles) {
    std::vector<Eigen::Vector3d> hull = hullPoints(obstacle);
    const Box box = boundsOf(hull);
    if (box.high.z() <= kFloorTop) continue;
    // Union with every cluster this body comes near (merging clusters it bridges).
    std::size_t target = clusters.size();
    for (std::size_t b = 0; b < bounds.size(); ++b) {
      if (!near(bounds[b], box, gap)) continue;
      const std::size_t other = clusterOf[b];
      if (target == clusters.size()) {
        target = other;
      } else if (other != target) {
        ObstacleCluster& into = clusters[target];
        ObstacleCluster& from = clusters[other];
        into.names.insert(into.names.end(), from.names.begin(), from.names.end());
        into.hull.insert(into.hull.end(), from.hull.begin(), from.hull.end());
        from.names.clear();
        from.hull.clear();
        for (std::size_t& c : clusterOf) c = c == other ? target : c;
      }
    }
    if (target == clusters.size()) clusters.emplace_back();
    clusters[target].names.push_back(obstacle.name);
    clusters[target].hull.insert(clusters[target].hull.end(), hull.begin(), hull.end());
    bounds.push_back(box);
    clusterOf.push_back(target);
  }
  clusters.erase(
      std::remove_if(clusters.begin(), clusters.end(), [](const ObstacleCluster& c) { return c.names.empty(); }),
      clusters.end());
  return clusters;
}

std::vector<ViaCandidate> viaCandidates(const ObstacleCluster& cluster, const Eigen::Vector3d& p,
                                        const Eigen::Vector3d& q, double clearance,
                                        const std::optional<Eigen::Vector3d>& side) {
  std::vector<ViaCandidate> candidates;
  const double length = (q - p).norm();
  if (length < 4.0 * kEndKeepOut || cluster.hull.empty()) return candidates;
  const Eigen::Vector3d along = (q - p) / length;
  const auto inside = [&](double x) { return std::clamp(x, kEndKeepOut, length - kEndKeepOut); };
  const Eigen::Vector3d across = side ? Eigen::Vector3d(*side - side->dot(along) * along) : Eigen::Vector3d::Zero();
  // Each hull point's offset from p, once, as three arrays: a link's Minkowski difference has hundreds of points, and
  // every plane below takes their heights and apex lifts as whole-array operations (Eigen vectorizes them; the same
  // operations in the same order per point as one point at a time).
  const auto count = static_cast<Eigen::Index>(cluster.hull.size());
  Eigen::ArrayXd dx(count), dy(count), dz(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    const Eigen::Vector3d offset = cluster.hull[static_cast<std::size_t>(i)] - p;
    dx[i] = offset.x();
    dy[i] = offset.y();
    dz[i] = offset.z();
  }
  const Eigen::ArrayXd xs = dx * along.x() + dy * along.y() + dz * along.z();  // place along the leg
  const double x0 = std::min(length, xs.minCoeff()), x1 = std::max(0.0, xs.maxCoeff());
  const double apexX = inside(0.5 * (x0 + x1));
  // How much a hull point's needed height lifts the apex (the legs from p and q to the apex are straight), 0 for
  // points beyond the leg's ends: the same for every plane and margin, so it is computed once (the divisions were
  // most of this function's time on links' Minkowski differences).
  Eigen::ArrayXd lift = Eigen::ArrayXd::Zero(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    const double x = xs[i];
    if (x > 0.0 && x < length) lift[i] = x <= apexX ? apexX / x : (length - apexX) / (length - x);
  }
  constexpr std::size_t kMarginCount = std::size(kMargins);
  candidates.reserve(2 * kPlaneSteps * kMarginCount);
  Eigen::ArrayXd heights(count), raised(count);
  for (int step = 0; step < kPlaneSteps; ++step) {
    const Eigen::Vector3d away = avoidanceDirection(along, 2.0 * M_PI * step / kPlaneSteps);
    if (across.norm() > 1e-6 && away.dot(across.normalized()) < kWithinSide) continue;
    // Height of each point above p in this plane; with the clearance, what it needs below the legs before a margin.
    heights = dx * away.x() + dy * away.y() + dz * away.z();
    const double height = std::max(0.0, heights.maxCoeff());
    raised = heights + clearance;
    for (std::size_t m = 0; m < kMarginCount; ++m) {
      const double margin = kMargins[m], offset = height + clearance + margin;
      // Apex over the middle: each hull point between p and q must stay below both legs. A point whose needed height
      // is not positive, or that lies beyond the leg's ends (lift 0), lifts it by nothing (a product of at most 0).
      const double apex = std::max(clearance + margin, ((raised + margin) * lift).maxCoeff());
      const double enter = inside(x0 - margin), leave = inside(x1 + margin);
      const Eigen::Vector3d entry = p + enter * along + offset * away;
      ViaCandidate over{{entry}, margin};
      if (leave - enter > 1e-3) over.points.push_back(p + leave * along + offset * away);
      candidates.push_back(std::move(over));
      if (apex <= kHighestApex) candidates.push_back({{p + apexX * along + apex * away}, margin});
    }
  }
  return candidates;
}

}  // namespace arcplan::planners
