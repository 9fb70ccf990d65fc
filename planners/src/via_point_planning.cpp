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
#include "arcplan/robot/kinematics.h"
#include "arm_contact.h"
#include "posture_test.h"
#include "route_search.h"
#include "via_points.h"

namespace arcplan::planners::detail {
namespace {

// Bodies closer than this form one cluster: the flange and wrist (~0.1 m across) cannot pass between.
constexpr double kClusterGap = 0.1;
// A route has at most this many via points (two clusters passed over a trapezoid each).
constexpr std::size_t kMaxViaPoints = 4;
// Routes walked before the search gives up (each walk costs ~0.1 ms), and routes taken from the queue
// in all (most are dropped by one posture test of a via point, ~10 us, and do not count as walked).
constexpr int kMaxRoutes = 300;
constexpr int kMaxRoutesTaken = 10 * kMaxRoutes;
// Legs blocked by the arm that get detours measured on the arm's postures (each ~1-3 ms: the first
// failures, on the straight line and the shortest routes, are where they pay): the first after this many
// walks, one more every kWalksPerDetour walks (all of them when the queue runs dry).
constexpr std::size_t kMaxDetourSearches = 8;
constexpr int kWalksBeforeDetours = 60, kWalksPerDetour = 10;
// Detours are probed every 2 cm: their postures keep this much (m) beyond the margin, so that the arm
// between two probes, and the blended corners, still keep the margin.
constexpr double kDetourSlack = 0.005;
// Via points of the lattice route (latticeDetour), tried once per query: after kWalksBeforeLattice walks once the arm
// has blocked a leg, or when the search is exhausted. After 25 walks rather than 300: on the generated suite 10 of the
// 12 answers that changed execute faster (forearm-beam-002 5.19 -> 4.17 s), 2 at most 0.4 % slower, and the arm-blocked
// beams take 14-33 ms instead of 38-80 ms (docs/planners.md).
constexpr std::size_t kMaxLatticeViaPoints = 10;
constexpr int kWalksBeforeLattice = 25;
// Blends shrink by halves down to this tangent length (m); below it the corner counts as failed.
constexpr double kSmallestBlend = 0.004;
// Trials spent shortening the route that validated (each at most one certified walk of the whole path,
// as much as the rest of a simple search). One: the first trial (the whole margin) gives most of the gain;
// on the generated suite 3 trials made 0.3 % shorter executions and took ~1 ms more on line problems.
constexpr int kMaxShorteningTrials = 1;

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

// Where a route probably fails, tested before it is walked: one IK solution and one distance query
// each instead of a certified walk up to there. The suspects are the clusters' centres (the route's
// nearest point; the arm above the tool passes them there too) and the TCP positions where earlier
// walks were rejected (the arm takes nearly the same posture within kSuspectReach of one).
constexpr double kProbeSpacing = 0.01;  // m between the route points considered
constexpr double kSuspectReach = 0.03;  // m from an earlier rejection within which a route is probed

struct Suspect {
  Eigen::Vector3d position;
  double reach;  // probe the route's nearest point only if it is this close
};

// The first probed configuration closer than the margin, as a walk rejected there.
std::optional<Walk> failingProbe(const ArcQuery& query, PostureTest& posture, const BlendedPath& path,
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
    if (q && !posture.keepsMargin(*q)) {
      Walk probed;
      probed.waypoints.status = ConversionStatus::Rejected;
      probed.waypoints.failedAtArcLength = arcLength;
      probed.rejected = RejectedMotion{*q, *q};
      return probed;
    }
  }
  return std::nullopt;
}

// Where on a route a walk failed: the leg it belongs to (after a corner: the leg that follows), and
// the corner when it was on that corner's blend.
struct FailureSite {
  std::size_t leg;
  std::optional<std::size_t> blend;
};

FailureSite siteOf(const BlendedPath& path, std::size_t viaCount, double failedAt) {
  for (std::size_t i = 0; i < viaCount; ++i) {
    const auto [from, to] = path.blendSpan(i);
    if (failedAt > to + 1e-12) continue;
    if (failedAt >= from - 1e-12) return {i + 1, i};
    return {i, std::nullopt};
  }
  return {viaCount, std::nullopt};
}

// The search of one auto-mode query: the route graph, what earlier walks taught about where routes
// fail, and the bodies met.
class ViaPointSearch {
public:
  explicit ViaPointSearch(const ArcQuery& query)
      : query_(query),
        clusters_(clusterObstacles(query.obstacles, kClusterGap)),
        search_(query.a.translation(), query.b.translation(), kMaxViaPoints),
        posture_(query),
        orientationHeld_(Eigen::Quaterniond(query.a.linear()).angularDistance(Eigen::Quaterniond(query.b.linear())) <
                         1e-12) {
    for (const ObstacleCluster& cluster : clusters_) {
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (const Eigen::Vector3d& p : cluster.hull) centre += p / static_cast<double>(cluster.hull.size());
      suspects_.push_back({centre, std::numeric_limits<double>::infinity()});
    }
  }

  ArcOutcome solve() {
    for (;;) {
      // One more blocked leg's detours every kWalksPerDetour walks past kWalksBeforeDetours.
      const auto due = static_cast<std::size_t>((walks_ - kWalksBeforeDetours) / kWalksPerDetour + 1);
      if (walks_ >= kWalksBeforeDetours) measureArmDetours(due);
      const std::optional<Route> route = search_.next();
      if (!route) {
        if (measureArmDetours(armLegs_.size())) continue;
        break;
      }
      if (query_.ptc()) return failed("time limit reached before a valid route was found (" + lastFailure() + ")");
      if (walks_ >= kMaxRoutes || static_cast<int>(search_.routesTried()) > kMaxRoutesTaken) break;
      if (!legsLongEnough(*route)) continue;
      const std::vector<Eigen::Vector3d> vias(route->points.begin() + 1, route->points.end() - 1);
      if (!viasClear(vias)) continue;
      ++walks_;
      if (std::optional<ArcOutcome> found = walkRoute(*route, vias)) return std::move(*found);
      if (armBlocked_ && walks_ >= kWalksBeforeLattice) {
        if (std::optional<ArcOutcome> found = latticeRoute()) return std::move(*found);
      }
    }
    routesWalked_ = static_cast<int>(search_.routesTried());
    if (armBlocked_ && !query_.ptc()) {
      if (std::optional<ArcOutcome> found = latticeRoute()) return std::move(*found);
    }
    std::ostringstream message;
    message << (query_.ptc() ? "time limit reached" : "no route through via points is valid") << " ("
            << search_.routesTried() << " routes walked of " << search_.routesQueued() << "; last: " << lastFailure()
            << ")";
    return failed(message.str());
  }

private:
  // The last resort of a search the arm kept failing: a way from start to goal through the arm's clear
  // postures (arm_contact.h, latticeDetour), walked as any route. Asked once per query: nothing after that.
  std::optional<ArcOutcome> latticeRoute() {
    if (latticeTried_) return std::nullopt;
    latticeTried_ = true;
    const Eigen::Vector3d a = query_.a.translation(), b = query_.b.translation();
    const Eigen::Quaterniond from(query_.a.linear()), to(query_.b.linear());
    const PostureClear clear = [&](const Eigen::Vector3d& position) {
      if (query_.ptc()) return false;  // out of time: nothing more is passable, the search ends
      // The tool's orientation as the path would have it about there (slerped along the chord).
      const double t = std::clamp((position - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-12), 0.0, 1.0);
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = from.slerp(t, to).toRotationMatrix();
      pose.translation() = position;
      return posture_.clearAt(pose, kDetourSlack);
    };
    const std::optional<ViaCandidate> way = latticeDetour(a, b, clear, kMaxLatticeViaPoints);
    if (!way) return std::nullopt;
    Route route{{a}, std::vector<double>(way->points.size(), way->margin), 0.0};
    route.points.insert(route.points.end(), way->points.begin(), way->points.end());
    route.points.push_back(b);
    if (!legsLongEnough(route)) return std::nullopt;
    return walkRoute(route, std::vector<Eigen::Vector3d>(way->points.begin(), way->points.end()));
  }

  // The via point's configuration keeps the margin (held orientation).
  bool viaPointClear(const Eigen::Vector3d& point) {
    Eigen::Isometry3d pose = query_.a;
    pose.translation() = point;
    return posture_.clearAt(pose);
  }

  // With a held orientation a via point's posture is known before the walk: tested first, and
  // remembered when it fails.
  bool viasClear(const std::vector<Eigen::Vector3d>& vias) {
    for (const Eigen::Vector3d& v : vias) {
      const std::array<double, 3> key{v.x(), v.y(), v.z()};
      if (blockedPoints_.count(key) > 0) return false;
      if (orientationHeld_ && !viaPointClear(v)) {
        blockedPoints_.insert(key);
        return false;
      }
    }
    return true;
  }

  // Walks the route, narrowing a blend where the walk fails on it: the answer when it validates;
  // nothing when the time is up or the failed leg was dropped from the graph.
  std::optional<ArcOutcome> walkRoute(const Route& route, const std::vector<Eigen::Vector3d>& vias) {
    std::vector<double> blends;
    for (std::size_t i = 0; i < vias.size(); ++i) blends.push_back(initialBlend(route.points, i, route.margins[i]));
    routesWalked_ = static_cast<int>(search_.routesTried());
    for (;;) {
      const BlendedPath path(query_.a, query_.b, vias, blends);
      const Walk walked = probeThenWalk(path);
      if (walked.ok()) return shortest(route, path, walked.waypoints);
      if (query_.ptc()) return std::nullopt;
      // A failure on a blend first narrows that blend; on a line (or a blend at its smallest) the
      // leg is dropped from the graph.
      const FailureSite site = siteOf(path, vias.size(), walked.waypoints.failedAtArcLength);
      if (site.blend && blends[*site.blend] > 2.0 * kSmallestBlend) {
        blends[*site.blend] *= 0.5;
        continue;
      }
      dropLeg(route, site.leg, walked);
      return std::nullopt;
    }
  }

  // The probes first, then the screen of the route's waypoints, then the certified walk; a rejection away
  // from every suspect adds one.
  Walk probeThenWalk(const BlendedPath& path) {
    if (std::optional<Walk> probed = failingProbe(query_, posture_, path, suspects_)) return std::move(*probed);
    JointConversionResult converted;
    std::optional<Walk> screened = query_.validator.screen(path, query_.startOnly(), query_.goal, &converted);
    Walk walked =
        screened ? std::move(*screened) : query_.validator.walk(path, query_.startOnly(), query_.goal, &converted);
    if (!walked.rejected) return walked;
    const Eigen::Vector3d rejectedAt = path.position(walked.waypoints.failedAtArcLength);
    const bool known = std::any_of(suspects_.begin(), suspects_.end(), [&](const Suspect& suspect) {
      return (suspect.position - rejectedAt).norm() < kProbeSpacing;
    });
    if (!known) suspects_.push_back({rejectedAt, kSuspectReach});
    return walked;
  }

  // The leg leaves the graph; when a cluster's body stopped the walk, that cluster's candidates
  // replace it.
  void dropLeg(const Route& route, std::size_t leg, const Walk& walked) {
    lastFailure_ = DroppedLeg{walked.waypoints.status, leg, route.points.size() - 2, {}, std::nullopt};
    if (!walked.rejected) {
      lastFailure_->reason = walked.waypoints.reason;
      search_.removeLeg(route, leg);
      return;
    }
    const Rejection& rejection = lastFailure_->rejection.emplace(query_.validator.explain(*walked.rejected));
    const auto cluster = std::find_if(clusters_.begin(), clusters_.end(), [&](const ObstacleCluster& c) {
      return std::any_of(c.names.begin(), c.names.end(), [&](const std::string& n) { return rejection.involves(n); });
    });
    if (cluster == clusters_.end()) {
      search_.removeLeg(route, leg);
      return;
    }
    for (const std::string& name : cluster->names) {
      if (rejection.involves(name) && std::find(obstacles_.begin(), obstacles_.end(), name) == obstacles_.end()) {
        obstacles_.push_back(name);
      }
    }
    search_.legFailed(route, leg, waysRound(*cluster, rejection, walked.rejected->to, route, leg));
  }

  // The cluster's candidates as the TCP sees it, and where a link above the tool met it, as that link
  // sees it (arm_contact.h): the TCP moved so that the link clears the cluster. Such a leg is also
  // kept for detours measured on the arm's postures (measureArmDetours).
  std::vector<ViaCandidate> waysRound(const ObstacleCluster& cluster, const Rejection& rejection,
                                      const robot::Vector6& refused, const Route& route, std::size_t leg) {
    const Eigen::Vector3d &p = route.points[leg], &q = route.points[leg + 1];
    const double margin = query_.validator.margin();
    std::vector<ViaCandidate> ways = viaCandidates(cluster, p, q, margin);
    std::vector<collision::Obstacle> bodies;
    for (const collision::Obstacle& obstacle : query_.obstacles) {
      if (std::count(cluster.names.begin(), cluster.names.end(), obstacle.name) > 0) bodies.push_back(obstacle);
    }
    const std::vector<ArmContact> contacts =
        armContacts(query_.model.robot(), query_.outlines, refused, rejection.pairs.collisions, bodies);
    if (!contacts.empty()) {
      armBlocked_ = true;
      if (armLegs_.size() < kMaxDetourSearches) armLegs_.push_back({route, leg, refused});
    }
    for (const ArmContact& contact : contacts) {
      const std::vector<ViaCandidate> more =
          viaCandidates(seenFromTheTcp(cluster, contact.outline), p, q, margin, contact.side);
      ways.insert(ways.end(), more.begin(), more.end());
    }
    return ways;
  }

  // The arm's detours (clearingDetours) of the legs the arm blocked, added as further ways round them.
  // Measured only once the cheap candidates had their chance (kWalksBeforeDetours walks, or the queue
  // ran dry), up to the first `upTo` legs: each costs ~100 posture tests, more than the walks of a search
  // the TCP's candidates end.
  // False when there was nothing left to measure.
  bool measureArmDetours(std::size_t upTo) {
    upTo = std::min(upTo, armLegs_.size());
    if (armLegsMeasured_ >= upTo) return false;
    for (; armLegsMeasured_ < upTo; ++armLegsMeasured_) {
      const ArmLeg& blocked = armLegs_[armLegsMeasured_];
      const Eigen::Vector3d &p = blocked.route.points[blocked.leg], &q = blocked.route.points[blocked.leg + 1];
      // The refused posture's tool orientation held across the leg (exact when the route holds it).
      Eigen::Isometry3d pose = robot::tipPose(query_.model.robot(), blocked.refused);
      const double at = std::clamp((pose.translation() - p).dot((q - p).normalized()), 0.0, (q - p).norm());
      const PostureClear clear = [&](const Eigen::Vector3d& position) {
        pose.translation() = position;
        return posture_.clearAt(pose, kDetourSlack);
      };
      search_.legFailed(blocked.route, blocked.leg, clearingDetours(p, q, blockedSpan(p, q, at, clear), clear));
    }
    return true;
  }

  // The margins come in steps: where a via point can come closer, the path gets shorter. Each trial
  // is checked like a route (via points, probes, then the certified walk); out of time, the route
  // that validated is the answer.
  ArcOutcome shortest(const Route& route, const BlendedPath& validated, JointConversionResult waypoints) {
    RouteShortening shortening(query_.a, query_.b, validated, route.margins, kMaxShorteningTrials);
    while (const std::optional<BlendedPath> candidate = shortening.next()) {
      if (query_.ptc()) break;
      const std::optional<Walk> walked = validatedWalk(*candidate);
      if (walked) waypoints = walked->waypoints;
      shortening.accept(walked.has_value());
    }
    const BlendedPath& best = shortening.best();
    ArcOutcome outcome;
    outcome.kind = best.points().size() == 2 ? ArcPlannerResult::Kind::StraightLine : ArcPlannerResult::Kind::ViaPoints;
    outcome.path = std::move(waypoints);
    outcome.obstacles = obstacles_;
    outcome.viaPoints.assign(best.points().begin() + 1, best.points().end() - 1);
    outcome.blends = best.blends();
    outcome.tcpPathLength = best.length();
    outcome.cartesianFraction = 1.0;
    outcome.routesTried = routesWalked_;
    return outcome;
  }

  // The walk of a shortening candidate when it validates.
  std::optional<Walk> validatedWalk(const BlendedPath& candidate) {
    for (std::size_t i = 0; i + 2 < candidate.points().size(); ++i) {
      if (orientationHeld_ && !viaPointClear(candidate.points()[i + 1])) return std::nullopt;
    }
    if (failingProbe(query_, posture_, candidate, suspects_)) return std::nullopt;
    JointConversionResult converted;
    if (query_.validator.screen(candidate, query_.startOnly(), query_.goal, &converted)) return std::nullopt;
    Walk walked = query_.validator.walk(candidate, query_.startOnly(), query_.goal, &converted);
    if (!walked.ok()) return std::nullopt;
    return walked;
  }

  ArcOutcome failed(std::string reason) const {
    ArcOutcome outcome = failure(std::move(reason));
    outcome.obstacles = obstacles_;
    outcome.routesTried = routesWalked_;
    return outcome;
  }

  const ArcQuery& query_;
  const std::vector<ObstacleCluster> clusters_;
  RouteSearch search_;
  PostureTest posture_;
  const bool orientationHeld_;
  std::vector<Suspect> suspects_;
  std::set<std::array<double, 3>> blockedPoints_;  // via points whose posture failed the margin
  // The last leg dropped, put in words only when a failure reports it (formatting it at every drop cost ~2 % of a
  // search that drops hundreds).
  struct DroppedLeg {
    ConversionStatus status = ConversionStatus::Success;
    std::size_t leg = 0, viaPoints = 0;
    std::string reason;                  // the walk's, when no motion was refused
    std::optional<Rejection> rejection;  // the refused motion's bodies
  };
  std::optional<DroppedLeg> lastFailure_;
  std::string lastFailure() const {
    if (!lastFailure_) return "no route";
    std::ostringstream text;
    text << toString(lastFailure_->status) << " on leg " << lastFailure_->leg + 1 << " of a route with "
         << lastFailure_->viaPoints << " via points: "
         << (lastFailure_->rejection ? lastFailure_->rejection->describe(query_.validator.margin())
                                     : lastFailure_->reason);
    return text.str();
  }
  std::vector<std::string> obstacles_;  // bodies that blocked a leg, in the order met
  int routesWalked_ = 0;                // routes tried when the last one was walked
  int walks_ = 0;                       // routes walked (or probed) so far
  bool armBlocked_ = false;             // a link above the tool stopped a walk
  bool latticeTried_ = false;           // latticeRoute() was asked (once per query)
  struct ArmLeg {
    Route route;
    std::size_t leg;
    robot::Vector6 refused;
  };
  std::vector<ArmLeg> armLegs_;  // legs the arm blocked, the first kMaxDetourSearches
  std::size_t armLegsMeasured_ = 0;
};

}  // namespace

ArcOutcome planViaPoints(const ArcQuery& query) { return ViaPointSearch(query).solve(); }

}  // namespace arcplan::planners::detail
