#include "arcplan/collision/endpoint_clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <fcl/geometry/shape/convex.h>

#include "arcplan/collision/motion_check.h"
#include "arcplan/common/error.h"
#include "model_implementation.h"
#include "motion_clearance.h"

namespace arcplan::collision {
namespace detail {

// A robot body (a link with geometry, or an attached object) in its link's frame, as points whose
// convex hull contains it (its parts' hull vertices, box corners) and balls (a sphere's or cylinder's
// bounding capsule by its two end balls). Its largest displacement is that of the robot's geometry, or a
// few millimetres more where a coarse hull stands in for a detailed mesh.
struct ZoneBody {
  int link = -1;  // index into robot().links()
  std::vector<Eigen::Vector3d> points;
  std::vector<std::pair<Eigen::Vector3d, double>> balls;  // centre, radius
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();       // mean of points and ball centres: inside the body's hull
  double radius = 0.0;                                    // the whole body lies within this of `centre`
  Eigen::VectorXd reach;  // per joint: the certified motion check's D_jL (motion_bounds.h), for these points
};

struct ZoneGeometry {
  std::shared_ptr<const robot::RobotModel> robot;
  std::vector<ZoneBody> bodies;
  std::vector<std::vector<Eigen::Isometry3d>> endpointPoses;  // per zone: the link poses at its endpoint
};

}  // namespace detail

namespace {

using detail::ZoneBody;
using detail::ZoneGeometry;
using Poses = std::vector<Eigen::Isometry3d>;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

void checkDistance(double value, const char* what) {
  if (!std::isfinite(value) || value < 0.0) {
    throw Error(std::string("endpoint clearance: ") + what + " must be a finite distance >= 0 m, got " +
                std::to_string(value));
  }
}

// The largest distance of any of `points` from its nearest point among `near` [m].
double farthestFrom(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& near) {
  double farthest = 0.0;
  for (const Eigen::Vector3d& point : points) {
    double nearest = kInfinity;
    for (const Eigen::Vector3d& other : near) nearest = std::min(nearest, (point - other).squaredNorm());
    farthest = std::max(farthest, nearest);
  }
  return std::sqrt(farthest);
}

ZoneBody makeBody(const detail::Implementation& impl, std::size_t body) {
  ZoneBody result;
  result.link = impl.linkCapsuleLink[body];
  // Points outside the geometry D_jL was measured on move faster than D_jL per radian, by at most their
  // distance from it per radian: the reach is raised by the farthest such distance.
  double outside = 0.0;
  for (const detail::Part& part : impl.robotParts) {
    if (part.body != static_cast<int>(body)) continue;
    const auto hull = std::dynamic_pointer_cast<const fcl::Convexd>(part.hullGeometry);
    const auto coarse = std::dynamic_pointer_cast<const fcl::Convexd>(part.coarseHullGeometry);
    std::vector<Eigen::Vector3d> points;
    if (coarse && hull) {
      // A mesh with many hull vertices: its coarse containing hull (convex_hull.h), a few millimetres
      // outside the mesh but with a few dozen vertices, which is what keeps a displacement cheap.
      points = coarse->getVertices();
      outside = std::max(outside, farthestFrom(points, hull->getVertices()) + 1e-9);
    } else if (hull) {
      points = hull->getVertices();  // pushed out by at most ~1e-12 m against rounding (convex_hull.h)
      outside = std::max(outside, 1e-9);
    } else if (!part.hullPoints.empty()) {
      points = part.hullPoints;  // box corners
    } else {
      result.balls.push_back({part.offset * part.capsule.start, part.capsule.radius});
      result.balls.push_back({part.offset * part.capsule.end, part.capsule.radius});
    }
    for (const Eigen::Vector3d& point : points) result.points.push_back(part.offset * point);
  }
  result.reach = impl.jointReach.row(static_cast<Eigen::Index>(body)).transpose();
  for (Eigen::Index j = 0; j < result.reach.size(); ++j) {
    if (impl.movedBy(static_cast<Eigen::Index>(body), j)) result.reach[j] += outside;
  }
  const std::size_t count = result.points.size() + result.balls.size();
  if (count == 0) return result;
  for (const auto& point : result.points) result.centre += point;
  for (const auto& [centre, radius] : result.balls) result.centre += centre;
  result.centre /= static_cast<double>(count);
  for (const auto& point : result.points) result.radius = std::max(result.radius, (point - result.centre).norm());
  for (const auto& [centre, radius] : result.balls)
    result.radius = std::max(result.radius, (centre - result.centre).norm() + radius);
  return result;
}

// ‖R_a − R_b‖ (spectral norm) of two rotations: 2·sin(θ/2), θ the angle of the rotation between them.
double rotationGap(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return std::sqrt(std::max(0.0, 3.0 - (a.transpose() * b).trace()));
}

// A point p of the body moves by |(R − R_e)·p + (t − t_e)| from its place at the endpoint, a convex
// function of p: its largest value over the body is taken at a hull vertex (or on a ball's surface,
// where it is at most the centre's + gap·radius), and lies between the centre's and that + gap·radius.
struct Span {
  double low, high;
};

Span bodySpan(const ZoneBody& body, const Eigen::Isometry3d& at, const Eigen::Isometry3d& endpoint) {
  const double centre = (at * body.centre - endpoint * body.centre).norm();
  return {centre, centre + rotationGap(at.linear(), endpoint.linear()) * body.radius};
}

double bodyDisplacement(const ZoneBody& body, const Eigen::Isometry3d& at, const Eigen::Isometry3d& endpoint) {
  const Eigen::Matrix3d turn = at.linear() - endpoint.linear();
  const Eigen::Vector3d shift = at.translation() - endpoint.translation();
  double squared = 0.0;
  for (const Eigen::Vector3d& point : body.points) squared = std::max(squared, (turn * point + shift).squaredNorm());
  double largest = std::sqrt(squared);
  const double gap = rotationGap(at.linear(), endpoint.linear());
  for (const auto& [centre, radius] : body.balls)
    largest = std::max(largest, (turn * centre + shift).norm() + gap * radius);
  return largest;
}

// Bounds of the largest displacement of any body between the two sets of link poses; exact (low ==
// high) unless the bodies' spans already settle which side of `length` it is on.
Span largestDisplacement(const ZoneGeometry& geometry, const Poses& at, const Poses& endpoint, double length) {
  Span largest{0.0, 0.0};
  for (const ZoneBody& body : geometry.bodies) {
    const Span span = bodySpan(body, at[body.link], endpoint[body.link]);
    largest = {std::max(largest.low, span.low), std::max(largest.high, span.high)};
  }
  if (largest.low > length || largest.high <= length) return largest;
  double exact = largest.low;
  for (const ZoneBody& body : geometry.bodies) {
    if (bodySpan(body, at[body.link], endpoint[body.link]).high > exact)
      exact = std::max(exact, bodyDisplacement(body, at[body.link], endpoint[body.link]));
  }
  return {exact, exact};
}

// The certified motion check's bound of the farthest any of the points moves on the straight joint
// motion between the two: at least the straight-line displacement (docs/collision.md, "Motion bounds").
double motionBound(const ZoneGeometry& geometry, const robot::JointRef& a, const robot::JointRef& b) {
  const Eigen::VectorXd steps = (b - a).cwiseAbs();
  double bound = 0.0;
  for (const ZoneBody& body : geometry.bodies) bound = std::max(bound, body.reach.dot(steps));
  return bound;
}

}  // namespace

EndpointClearance::EndpointClearance(double clearance, double motionClearance)
    : clearance_(clearance), motionClearance_(std::max(clearance, motionClearance)) {
  checkDistance(clearance, "clearance");
  checkDistance(motionClearance, "motion clearance");
}

EndpointClearance::EndpointClearance(const CollisionModel& model, double clearance, double motionClearance,
                                     const std::vector<robot::JointVector>& endpoints)
    : EndpointClearance(clearance, motionClearance) {
  const int dof = model.robot().dof();
  // A certified motion rejects a pair measured closer than its own m + acceptance margin (m = c_m from
  // obstacles, requiredDistance(true, c_m) between the robot's own bodies), so an endpoint with a pair
  // closer than that could never be reached or left at c_m, even one a little above its m.
  const auto reachable = [&](bool self) {
    const double m = requiredDistance(self, motionClearance_);
    return m + acceptanceMargin(m);
  };
  CollisionData data(model);
  for (const robot::JointVector& endpoint : endpoints) {
    if (endpoint.size() != dof) {
      throw Error("endpoint clearance: an endpoint has " + std::to_string(endpoint.size()) + " joints, the robot " +
                  std::to_string(dof));
    }
    // Most endpoints keep that: the spheres and bounds of keepsAcceptanceMargin (the same distances) say so without
    // the exact distance of every pair (8 % of a quick arc query's time).
    if (motionClearance_ > 0.0 && keepsAcceptanceMargin(model, data, endpoint, motionClearance_)) continue;
    const DistanceReport measured = distance(model, data, endpoint);
    // e: the closest pair a certified motion at c_m cannot leave. That is clearanceOf(measured) (the clearance
    // the endpoint meets), or a self pair between kSelfClearance and its reachable distance: one that meets
    // the rule but no motion at c_m may start from (it is then the smaller of the two).
    const bool selfTooClose = measured.selfDistance < reachable(true);
    const double e =
        std::min(clearanceOf(measured), selfTooClose ? measured.selfDistance : std::numeric_limits<double>::infinity());
    if (!(e > 0.0) || !(selfTooClose || measured.obstacleDistance < reachable(false)))
      continue;  // in contact (stays invalid), or clear enough
    const double relaxed = kApproachZoneFraction * e;
    zones_.push_back({endpoint, e, std::min(clearance_, relaxed),
                      std::max(detail::kSmallestMinimumClearance, std::min(motionClearance_, relaxed))});
  }
  if (zones_.empty()) return;
  auto geometry = std::make_shared<ZoneGeometry>();
  geometry->robot = model.sharedRobot();
  const detail::Implementation& impl = detail::implementationOf(model);
  for (std::size_t body = 0; body < impl.linkCapsuleLink.size(); ++body)
    geometry->bodies.push_back(makeBody(impl, body));
  robot::KinematicsData poses(model.robot());
  for (const ApproachZone& zone : zones_) {
    robot::forwardKinematics(model.robot(), zone.endpoint, poses);
    geometry->endpointPoses.push_back(poses.linkPoses);
  }
  geometry_ = std::move(geometry);
}

double EndpointClearance::smallestStateClearance() const {
  double smallest = clearance_;
  for (const ApproachZone& zone : zones_) smallest = std::min(smallest, zone.stateClearance);
  return smallest;
}

bool EndpointClearance::inZone(std::size_t zone, const robot::JointRef& q,
                               std::optional<robot::KinematicsData>& poses) const {
  // The bound settles most states near the endpoint without forward kinematics.
  if (motionBound(*geometry_, zones_[zone].endpoint, q) <= kApproachZoneLength) return true;
  if (!poses) {
    poses.emplace(*geometry_->robot);
    robot::forwardKinematics(*geometry_->robot, q, *poses);
  }
  return largestDisplacement(*geometry_, poses->linkPoses, geometry_->endpointPoses[zone], kApproachZoneLength).high <=
         kApproachZoneLength;
}

std::vector<std::pair<double, double>> EndpointClearance::insideParts(std::size_t zone, const robot::JointRef& qa,
                                                                      const robot::JointRef& qb) const {
  // Conservative advancement on the displacement d(s) from the endpoint: along the motion no point moves
  // faster than `rate` per unit of s, so d changes at most that fast. A state measured d <= L proves
  // the states within (L − d)/rate of it inside the zone. The steps shrink toward the zone's edge: within
  // kEdgeBand of it a step of kEdgeBand/rate (at least 1/1024 of the motion) is taken, and a new inside part
  // starts only at d <= L − kEdgeBand, so a motion crossing the edge once gets one inside part. Each end is
  // walked inward while the motion is inside, up to its first state outside; what lies between keeps c_m
  // (conservative) without being proven outside: a straight joint motion seldom leaves a 10 cm zone and comes
  // back, and proving the outside too took 20–30 forward kinematics per motion leaving the goal (MBM
  // bookshelf_thin 0047: a sixth of RRTConnect's solve time). A single state (rate 0) crosses nothing: it is
  // inside whenever d <= L, as stateClearanceAt judges it.
  // Parts are proven against L − kProofSlack: stateClearanceAt recomputes d at a part's end by another
  // forward kinematics of an interpolated state, whose rounding must not put it outside (a single state is
  // not interpolated).
  constexpr double kEdgeBand = 2e-3;    // m
  constexpr double kProofSlack = 1e-9;  // m
  constexpr double kSmallestStep = 1.0 / 1024.0;
  const double rate = motionBound(*geometry_, qa, qb);
  const auto within = [&](double length) { return rate > 0.0 ? length / rate : kInfinity; };
  const double edgeStep = std::max(kSmallestStep, within(kEdgeBand));
  const double edge = rate > 0.0 ? kApproachZoneLength - kProofSlack : kApproachZoneLength;
  const double startBelow = rate > 0.0 ? edge - kEdgeBand : edge;
  robot::KinematicsData poses(*geometry_->robot);
  // From `from` toward `to` (t in [0, limit] of the way): the inside parts in t, in order; returns the t of the
  // first state outside, or 1 when the walk proved the motion inside up to `limit`.
  const auto walk = [&](const robot::JointRef& from, const robot::JointRef& to, double limit,
                        std::vector<std::pair<double, double>>& parts) {
    const robot::JointVector delta = to - from;
    for (double t = 0.0;;) {
      robot::forwardKinematics(*geometry_->robot,
                               t == 1.0 ? robot::JointVector(to) : robot::JointVector(from + t * delta), poses);
      const Span d = largestDisplacement(*geometry_, poses.linkPoses, geometry_->endpointPoses[zone], edge);
      if (d.high > edge) return t;
      double proven = t;  // inside, or in the edge band, up to here
      const double before = std::max(0.0, t - within(edge - d.high)), after = std::min(1.0, t + within(edge - d.high));
      if (!parts.empty() && before <= parts.back().second) {
        parts.back().second = std::max(parts.back().second, after);
        proven = after;
      } else if (d.high <= startBelow) {
        parts.emplace_back(before, after);
        proven = after;
      }
      if (proven >= limit || t == 1.0) return 1.0;
      t = std::min(1.0, std::max(proven, t + edgeStep));
    }
  };
  std::vector<std::pair<double, double>> parts, fromEnd;
  const double stopped = walk(qa, qb, 1.0, parts);
  if (stopped >= 1.0) return parts;
  walk(qb, qa, 1.0 - stopped, fromEnd);
  // The end's parts in s = 1 − t, in order; one that reaches a start part joins it.
  for (auto part = fromEnd.rbegin(); part != fromEnd.rend(); ++part) {
    const double from = 1.0 - part->second, to = 1.0 - part->first;
    if (!parts.empty() && from <= parts.back().second)
      parts.back().second = std::max(parts.back().second, to);
    else
      parts.emplace_back(from, to);
  }
  return parts;
}

std::vector<MotionPiece> EndpointClearance::motionPieces(const robot::JointRef& qa, const robot::JointRef& qb) const {
  struct Interval {
    double from, to, clearance;
  };
  std::vector<Interval> inside;
  std::vector<double> cuts{0.0, 1.0};
  for (std::size_t zone = 0; zone < zones_.size(); ++zone) {
    if (zones_[zone].motionClearance >= motionClearance_) continue;
    for (const auto& [from, to] : insideParts(zone, qa, qb)) {
      inside.push_back({from, to, zones_[zone].motionClearance});
      cuts.push_back(from);
      cuts.push_back(to);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<MotionPiece> pieces;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double from = cuts[k], to = cuts[k + 1];
    if (!(to > from)) continue;
    double required = motionClearance_;
    for (const Interval& part : inside) {
      if (part.from <= from && to <= part.to) required = std::min(required, part.clearance);
    }
    if (!pieces.empty() && pieces.back().clearance == required) {
      pieces.back().to = to;
    } else {
      pieces.push_back({from, to, required});
    }
  }
  return pieces;
}

double EndpointClearance::stateClearanceAt(const robot::JointRef& q) const {
  double required = clearance_;
  std::optional<robot::KinematicsData> poses;
  for (std::size_t zone = 0; zone < zones_.size(); ++zone) {
    if (zones_[zone].stateClearance < required && inZone(zone, q, poses)) required = zones_[zone].stateClearance;
  }
  return required;
}

double EndpointClearance::motionClearanceAt(const robot::JointRef& q) const {
  double required = motionClearance_;
  std::optional<robot::KinematicsData> poses;
  for (std::size_t zone = 0; zone < zones_.size(); ++zone) {
    if (zones_[zone].motionClearance < required && inZone(zone, q, poses)) required = zones_[zone].motionClearance;
  }
  return required;
}

}  // namespace arcplan::collision
