// The auto mode of the arc planner: the shortest route through via points that validates, corners
// blended as widely as validates (docs/planners.md).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

#include "arc_planning.h"
#include "arcplan/planners/blended_path.h"
#include "arcplan/planners/route_search.h"
#include "arcplan/planners/via_points.h"

namespace arcplan::planners::detail {
namespace {

// Bodies closer than this form one cluster: the flange and wrist (~0.1 m across) cannot pass between.
constexpr double kClusterGap = 0.1;
// A route has at most this many via points (two clusters passed over a trapezoid each).
constexpr std::size_t kMaxViaPoints = 4;
// Routes walked before the search gives up (each walk costs ~0.1 ms).
constexpr int kMaxRoutes = 300;
// Blends shrink by halves down to this tangent length (m); below it the corner counts as failed.
constexpr double kSmallestBlend = 0.004;
// Trials spent shortening the route that validated (each at most one walk, ~0.1 ms).
constexpr int kMaxShorteningTrials = 3;

// The blend a corner starts with: the largest that fits, but whose arc does not cut the corner by more
// than half the margin its via point keeps (t·tan(φ/4) inside the corner).
double initialBlend(const std::vector<Eigen::Vector3d>& points, std::size_t i, double margin) {
  const double largest = BlendedPath::maxBlend(points, i);
  const double quarterTurn = std::tan(0.25 * BlendedPath::turningAngle(points, i + 1));
  return quarterTurn > 1e-9 ? std::min(largest, 0.5 * margin / quarterTurn) : largest;
}

bool legsLongEnough(const Route& route) {
  for (std::size_t k = 0; k + 1 < route.points.size(); ++k) {
    if ((route.points[k + 1] - route.points[k]).norm() < 2.0 * kSmallestBlend) return false;
  }
  return true;
}

// The configuration at a TCP pose on the start's branch (what a walk would reach there).
std::optional<robot::Vector6> postureAt(const ArcQuery& query, const Eigen::Isometry3d& pose) {
  return query.ik.solveBranch(pose, query.ik.branchOf(query.start), query.start[5]);
}

// The via point's configuration keeps the margin: a cheap test before a walk (held orientation).
bool viaPointClear(const ArcQuery& query, const Eigen::Vector3d& point) {
  Eigen::Isometry3d pose = query.a;
  pose.translation() = point;
  const auto q = postureAt(query, pose);
  return q && query.validator.keepsMargin(*q);
}

// Where a route probably fails, tested before it is walked: one IK solution and one distance query
// each instead of a certified walk up to there. The suspects are the clusters' centres (the route's
// nearest point; the arm above the tool passes them there too) and the TCP positions where earlier
// walks were rejected (the arm takes nearly the same posture within kSuspectReach of one). Returns
// the arc length of the first probed configuration closer than the margin (the validator's
// rejection() then names the pair).
constexpr double kProbeSpacing = 0.01;  // m between the route points considered
constexpr double kSuspectReach = 0.03;  // m from an earlier rejection within which a route is probed

struct Suspect {
  Eigen::Vector3d position;
  double reach;  // probe the route's nearest point only if it is this close
};

std::optional<double> failingProbe(const ArcQuery& query, const BlendedPath& path,
                                   const std::vector<Suspect>& suspects) {
  const int count = static_cast<int>(std::ceil(path.length() / kProbeSpacing));
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k <= count; ++k) points.push_back(path.position(path.length() * k / count));
  std::set<int> probes;
  for (const Suspect& suspect : suspects) {
    int nearest = 0;
    for (int k = 1; k <= count; ++k) {
      if ((points[k] - suspect.position).squaredNorm() < (points[nearest] - suspect.position).squaredNorm())
        nearest = k;
    }
    if ((points[nearest] - suspect.position).norm() <= suspect.reach) probes.insert(nearest);
  }
  for (const int k : probes) {  // in order along the route, as a walk would meet them
    const double arcLength = path.length() * k / count;
    const auto q = postureAt(query, path.pose(arcLength));
    if (q && !query.validator.keepsMargin(*q)) return arcLength;
  }
  return std::nullopt;
}

}  // namespace

JointWaypoints planViaPoints(const ArcQuery& query, ArcPlannerResult& result) {
  const std::vector<ObstacleCluster> clusters = clusterObstacles(query.obstacles, kClusterGap);
  RouteSearch search(query.a.translation(), query.b.translation(), kMaxViaPoints);
  std::vector<Suspect> suspects;
  for (const ObstacleCluster& cluster : clusters) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : cluster.hull) centre += p / static_cast<double>(cluster.hull.size());
    suspects.push_back({centre, std::numeric_limits<double>::infinity()});
  }
  const bool orientationHeld =
      Eigen::Quaterniond(query.a.linear()).angularDistance(Eigen::Quaterniond(query.b.linear())) < 1e-12;
  std::set<std::array<double, 3>> blockedPoints;
  std::string lastFailure = "no route";
  while (const std::optional<Route> route = search.next()) {
    if (query.ptc()) {
      result.reason = "time limit reached before a valid route was found (" + lastFailure + ")";
      return {};
    }
    if (static_cast<int>(search.routesTried()) > kMaxRoutes) break;
    if (!legsLongEnough(*route)) continue;
    const std::vector<Eigen::Vector3d> vias(route->points.begin() + 1, route->points.end() - 1);
    // With a held orientation a via point's posture is known before the walk: test it first.
    bool viasClear = true;
    for (const Eigen::Vector3d& v : vias) {
      const std::array<double, 3> key{v.x(), v.y(), v.z()};
      if (blockedPoints.count(key) > 0) viasClear = false;
      if (viasClear && orientationHeld && !viaPointClear(query, v)) {
        blockedPoints.insert(key);
        viasClear = false;
      }
    }
    if (!viasClear) continue;
    std::vector<double> blends;
    for (std::size_t i = 0; i < vias.size(); ++i) blends.push_back(initialBlend(route->points, i, route->margins[i]));
    result.routesTried = static_cast<int>(search.routesTried());
    for (;;) {
      const BlendedPath path(query.a, query.b, vias, blends);
      JointWaypoints walked;
      if (const std::optional<double> probedFailure = failingProbe(query, path, suspects)) {
        walked.status = ConversionStatus::Rejected;
        walked.failedAtArcLength = *probedFailure;
      } else {
        walked = query.validator.walk(path, query.startOnly(), query.goal);
        const Eigen::Vector3d rejectedAt = path.position(walked.failedAtArcLength);
        const bool known = std::any_of(suspects.begin(), suspects.end(), [&](const Suspect& suspect) {
          return (suspect.position - rejectedAt).norm() < kProbeSpacing;
        });
        if (walked.status == ConversionStatus::Rejected && !known) suspects.push_back({rejectedAt, kSuspectReach});
      }
      if (walked.ok()) {
        // The margins come in steps: where a via point can come closer, the path gets shorter. Each
        // trial is checked like a route (via points, probes, then the certified walk).
        const BlendedPath shortest = shortenRoute(
            query.a, query.b, path, route->margins, kMaxShorteningTrials, [&](const BlendedPath& candidate) {
              if (query.ptc()) return false;  // out of time: the route that validated is the answer
              for (std::size_t i = 0; i + 2 < candidate.points().size(); ++i) {
                if (orientationHeld && !viaPointClear(query, candidate.points()[i + 1])) return false;
              }
              if (failingProbe(query, candidate, suspects)) return false;
              JointWaypoints candidateWalk = query.validator.walk(candidate, query.startOnly(), query.goal);
              if (!candidateWalk.ok()) return false;
              walked = std::move(candidateWalk);
              return true;
            });
        result.kind = vias.empty() ? ArcPlannerResult::Kind::StraightLine : ArcPlannerResult::Kind::ViaPoints;
        result.viaPoints.assign(shortest.points().begin() + 1, shortest.points().end() - 1);
        result.blends = shortest.blends();
        result.tcpPathLength = shortest.length();
        return walked;
      }
      if (query.ptc()) break;
      const double failedAt = walked.failedAtArcLength;
      // A failure on a blend first narrows that blend; on a line (or a blend at its smallest) the
      // leg is dropped from the graph.
      std::size_t leg = vias.size();
      bool narrowed = false;
      for (std::size_t i = 0; i < vias.size(); ++i) {
        const auto [from, to] = path.blendSpan(i);
        if (failedAt > to + 1e-12) continue;
        if (failedAt >= from - 1e-12 && blends[i] > 2.0 * kSmallestBlend) {
          blends[i] *= 0.5;
          narrowed = true;
        }
        leg = failedAt >= from - 1e-12 ? i + 1 : i;
        break;
      }
      if (narrowed) continue;
      std::ostringstream failure;
      failure << toString(walked.status) << " on leg " << leg + 1 << " of a route with " << vias.size()
              << " via points";
      if (walked.status != ConversionStatus::Rejected) {
        lastFailure = failure.str() + ": " + walked.reason;
        search.removeLeg(*route, leg);
        break;
      }
      const Rejection rejection = query.validator.rejection();
      lastFailure = failure.str() + ": " + rejection.describe(query.validator.margin());
      const auto cluster = std::find_if(clusters.begin(), clusters.end(), [&](const ObstacleCluster& c) {
        return std::any_of(c.names.begin(), c.names.end(), [&](const std::string& n) { return rejection.involves(n); });
      });
      if (cluster == clusters.end()) {
        search.removeLeg(*route, leg);
        break;
      }
      for (const std::string& name : cluster->names) {
        if (rejection.involves(name) &&
            std::find(result.obstacles.begin(), result.obstacles.end(), name) == result.obstacles.end()) {
          result.obstacles.push_back(name);
        }
      }
      search.legFailed(*route, leg,
                       viaCandidates(*cluster, route->points[leg], route->points[leg + 1], query.validator.margin()));
      break;
    }
  }
  result.routesTried = static_cast<int>(search.routesTried());
  std::ostringstream message;
  message << (query.ptc() ? "time limit reached" : "no route through via points is valid") << " ("
          << search.routesTried() << " routes walked of " << search.routesQueued() << "; last: " << lastFailure << ")";
  result.reason = message.str();
  return {};
}

}  // namespace arcplan::planners::detail
