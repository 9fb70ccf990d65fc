#include "arcplan/collision/motion_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "arcplan/common/error.h"
#include "model_implementation.h"
#include "motion_bounds.h"
#include "sphere_prefilter.h"

namespace arcplan::collision {
namespace {

using detail::Implementation;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Exact distances are GJK's, which docs/collision.md measured exact to 1e-6 m; certificates take
// them this much smaller so they never rest on an overestimate.
constexpr double kDistanceSlack = 1e-6;
// The smallest minimumClearance accepted: it must stay well above kDistanceSlack, or a pair just
// above it would certify (almost) no step.
constexpr double kSmallestMinimumClearance = 1e-5;
// A pair whose certificate runs out within this fraction of its last step after the front is
// measured again at the front already, so that one forward kinematics serves several pairs. On the
// long motions of perf/perf_collision.cpp 0 (only the pairs at the front) takes 1.8x the time of
// 0.5, 0.3–0.7 are within 7 % of it, 1 (every pair every time) takes 1.2x.
constexpr double kEarlyMeasurement = 0.5;

// A point of a body's geometry with a radius: the body lies inside the convex hull of these balls.
struct BoundingBall {
  Eigen::Vector3d center;
  double radius;
};

// Pose of `to`'s frame before its own joint rotation, in `from`'s frame, for a descendant `to`
// reached through fixed joints only (apart from `to`'s own).
Eigen::Isometry3d chainOrigin(const robot::RobotModel& robot, int from, int to) {
  Eigen::Isometry3d pose = robot.links()[to].originInParent;
  for (int l = robot.links()[to].parent; l != from; l = robot.links()[l].parent) {
    pose = robot.links()[l].originInParent * pose;
  }
  return pose;
}

double farthestDistance(const std::vector<BoundingBall>& balls, const Eigen::Isometry3d& toFrame) {
  double farthest = 0.0;
  for (const auto& ball : balls) farthest = std::max(farthest, (toFrame * ball.center).norm() + ball.radius);
  return farthest;
}

// The largest distance of the balls from the axis through the origin along the unit `axis`.
double farthestFromAxis(const std::vector<BoundingBall>& balls, const Eigen::Isometry3d& toFrame,
                        const Eigen::Vector3d& axis) {
  double farthest = 0.0;
  for (const auto& ball : balls) {
    const Eigen::Vector3d p = toFrame * ball.center;
    farthest = std::max(farthest, (p - p.dot(axis) * axis).norm() + ball.radius);
  }
  return farthest;
}

// Per joint: how fast the distance between bodies a and b can shrink per radian of that joint. In
// the frame of their nearest common ancestor only the joints that move one and not the other move
// anything, each moving points of its body at most its reach.
Eigen::VectorXd relativeReach(const Implementation& impl, int a, int b) {
  Eigen::VectorXd reach = Eigen::VectorXd::Zero(impl.jointReach.cols());
  for (Eigen::Index j = 0; j < reach.size(); ++j) {
    if (impl.movedBy(a, j) != impl.movedBy(b, j)) {
      reach[j] = impl.movedBy(a, j) ? impl.jointReach(a, j) : impl.jointReach(b, j);
    }
  }
  return reach;
}

void checkJoints(const CollisionModel& model, const robot::JointRef& qa, const robot::JointRef& qb) {
  if (qa.size() != model.robot().dof() || qb.size() != model.robot().dof()) {
    throw Error("motion check: expected " + std::to_string(model.robot().dof()) + " joint values per end, got " +
                std::to_string(qa.size()) + " and " + std::to_string(qb.size()));
  }
  if (!qa.allFinite() || !qb.allFinite()) throw Error("motion check: joint values must be finite numbers");
}

void checkBody(const CollisionModel& model, int body) {
  if (body < 0 || body >= static_cast<int>(model.linkNames().size())) {
    throw Error("motion bound: link index " + std::to_string(body) + " is not one of the " +
                std::to_string(model.linkNames().size()) + " links with collision geometry");
  }
}

struct PairMeasurement {
  double gap;     // lower bound of the pair's distance [m]
  bool tooClose;  // an exact distance below minimumClearance
};

// A lower bound of the group's distance in the current configuration (updateRobot): the capsule
// bounds when they reach `wanted` (the gap that would certify the rest of the motion) or
// minimumClearance, else the exact distances of the part pairs whose bounds are below. On arcplan's
// UR10e the capsules are tight enough that exact distances for larger bounds cost more (2.5 µs per
// GJK call) than the steps they save: below 2 cm they made the long motions of
// perf/perf_collision.cpp 2–2.4x slower.
PairMeasurement measurePair(const CollisionModel& model, detail::Workspace& data,
                            const Implementation::PairGroup& group, double wanted, double minimumClearance) {
  const Implementation& impl = detail::implementationOf(model);
  if (group.rigid) return {group.rigidDistance - kDistanceSlack, group.rigidDistance < minimumClearance};
  double gap = detail::linkGap(impl, data, group);
  if (gap >= wanted) return {gap, false};
  double partGap = kInfinity;
  for (const auto& [i, j] : group.parts) partGap = std::min(partGap, detail::boundGap(impl, data, i, j, group.self));
  gap = std::max(gap, partGap);
  if (gap >= minimumClearance) return {gap, false};
  double exact = kInfinity;
  for (const auto& [i, j] : group.parts) {
    const double bound = detail::boundGap(impl, data, i, j, group.self);
    // A part pair bounded above the smallest distance so far cannot lower it, and one bounded
    // above `wanted` certifies enough with its bound.
    if (bound >= std::min(wanted, exact)) {
      exact = std::min(exact, bound);
      continue;
    }
    const auto &first = impl.robotParts[i], &second = detail::secondPart(impl, group, j);
    const Eigen::Isometry3d& secondPose = detail::secondPose(impl, data, group, j);
    // The hulls' lower bound (cheaper than the BVHs) will do unless closer than minimumClearance.
    const double hull = detail::hullGap(first, data.partPoses[i], second, secondPose, model.options());
    if (hull >= std::min(minimumClearance, exact)) {
      exact = std::min(exact, hull);
      continue;
    }
    const double d = detail::partsDistance(first, data.partPoses[i], second, secondPose, bound <= 0.0, model.options());
    if (d < minimumClearance) return {d, true};
    exact = std::min(exact, d - kDistanceSlack);
  }
  return {std::max(gap, exact), false};
}

// Conservative advancement from both ends, or only from the start when the last valid state is
// wanted. Pair k is proven apart before motionPairs[k].certifiedFromStart and after
// certifiedFromEnd (open intervals: a pair at distance g at s stays apart on (s − g/rate,
// s + g/rate)); it is done when the two overlap. The front on each side is the smallest
// certificate of the pairs not done, and the pairs whose certificate ends there (or soon after)
// are measured there.
bool certifiedMotionFree(const CollisionModel& model, detail::Workspace& data, const robot::JointRef& qa,
                         const robot::JointRef& qb, double* lastValidFraction, double minimumClearance) {
  const Implementation& impl = detail::implementationOf(model);
  // The sphere prefilter first: it certifies most motions with a few batches of 8 states.
  const detail::SphereMotion spheres = detail::sphereMotion(model, data, qa, qb, minimumClearance);
  if (spheres == detail::SphereMotion::Free) return true;
  if (spheres == detail::SphereMotion::Collides && lastValidFraction == nullptr) return false;
  auto& pairs = data.motionPairs;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    pairs[k] = {impl.groups[k]->relativeReach.dot((qb - qa).cwiseAbs()), 0.0, 1.0, 0.0, 1.0};
  }
  const auto done = [](const detail::Workspace::MotionPair& pair) {
    return pair.certifiedFromStart > pair.certifiedFromEnd;
  };
  const bool bothEnds = lastValidFraction == nullptr;
  bool atStart = true;
  double lastClear = 0.0;  // the last start-side front measured clear
  while (true) {
    double front = kInfinity, back = -kInfinity;
    for (const auto& pair : pairs) {
      if (done(pair)) continue;
      front = std::min(front, pair.certifiedFromStart);
      back = std::max(back, pair.certifiedFromEnd);
    }
    if (front == kInfinity) return true;
    const double s = atStart ? front : back;
    data.motionJoints = qa + s * (qb - qa);
    detail::updateRobot(model, data, data.motionJoints);
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      auto& pair = pairs[k];
      if (done(pair)) continue;
      const double ahead = atStart ? pair.certifiedFromStart - s : s - pair.certifiedFromEnd;
      const double lastStep =
          atStart ? pair.certifiedFromStart - pair.measuredFromStart : pair.measuredFromEnd - pair.certifiedFromEnd;
      if (ahead > kEarlyMeasurement * lastStep) continue;
      const double remaining = atStart ? pair.certifiedFromEnd - s : s - pair.certifiedFromStart;
      const PairMeasurement measured = measurePair(model, data, *impl.groups[k],
                                                   std::max(pair.rate * remaining, minimumClearance), minimumClearance);
      if (measured.tooClose) {
        if (lastValidFraction != nullptr) *lastValidFraction = lastClear;
        return false;
      }
      const double reach = measured.gap / pair.rate;  // +infinity for a pair the motion does not move
      // A pair measured before its certificate ran out keeps the longer one.
      if (atStart) {
        pair.certifiedFromStart = std::max(pair.certifiedFromStart, s + reach);
        pair.measuredFromStart = s;
      } else {
        pair.certifiedFromEnd = std::min(pair.certifiedFromEnd, s - reach);
        pair.measuredFromEnd = s;
      }
    }
    if (atStart) lastClear = s;
    if (bothEnds) atStart = !atStart;
  }
}

bool discreteMotionFree(const CollisionModel& model, CollisionData& data, const robot::JointRef& qa,
                        const robot::JointRef& qb, double* lastValidFraction, double maxJointStep) {
  const int segments = discreteSegmentCount(qa, qb, maxJointStep);
  const auto freeAt = [&](int k) {
    if (k == segments) return isCollisionFree(model, data, qb);
    robot::JointVector& q = detail::workspaceOf(data).motionJoints;
    q = qa + (static_cast<double>(k) / segments) * (qb - qa);
    return isCollisionFree(model, data, q);
  };
  if (lastValidFraction != nullptr) {
    for (int k = 1; k <= segments; ++k) {
      if (!freeAt(k)) {
        *lastValidFraction = static_cast<double>(k - 1) / segments;
        return false;
      }
    }
    return true;
  }
  // The end, then the intermediate states in bisection order (each index k once, coarse strides
  // first), so a blocked motion is usually rejected after a few checks.
  if (!freeAt(segments)) return false;
  int stride = 1;
  while (2 * stride < segments) stride *= 2;
  for (; stride >= 1; stride /= 2) {
    for (int k = stride; k < segments; k += 2 * stride) {
      if (!freeAt(k)) return false;
    }
  }
  return true;
}

}  // namespace

namespace detail {

void computeMotionBounds(const robot::RobotModel& robot, Implementation& impl) {
  const std::size_t bodies = impl.linkCapsules.size();
  std::vector<std::vector<BoundingBall>> balls(bodies);
  for (const Part& part : impl.robotParts) {
    if (part.hullPoints.empty()) {
      balls[part.body].push_back({part.offset * part.capsule.start, part.capsule.radius});
      balls[part.body].push_back({part.offset * part.capsule.end, part.capsule.radius});
    }
    for (const auto& point : part.hullPoints) balls[part.body].push_back({part.offset * point, 0.0});
  }
  impl.jointReach = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(bodies), robot.dof());
  impl.movedBy.setConstant(static_cast<Eigen::Index>(bodies), robot.dof(), false);
  for (std::size_t b = 0; b < bodies; ++b) {
    const int link = impl.linkCapsuleLink[b];
    // The moving links from the body's link toward the base: movers[0] is the nearest one.
    std::vector<int> movers;
    for (int l = link; l >= 0; l = robot.links()[l].parent) {
      if (robot.links()[l].joint >= 0) movers.push_back(l);
    }
    if (movers.empty()) continue;
    // Geometry in the frame of the nearest moving link (through fixed joints only).
    const Eigen::Isometry3d geometryInNearest =
        link == movers[0] ? Eigen::Isometry3d::Identity() : chainOrigin(robot, movers[0], link);
    const double farthestFromNearest = farthestDistance(balls[b], geometryInNearest);
    // Between moving links the offsets are rigid: |o_next − o_previous| never changes.
    double outerChain = 0.0;  // |o_movers[0] − o_movers[1]| + ... + |o_movers[k-2] − o_movers[k-1]|
    for (std::size_t k = 0; k < movers.size(); ++k) {
      const robot::Link& mover = robot.links()[movers[k]];
      double reach = 0.0;
      if (k == 0) {
        // Rigidly attached to the joint's own link: exactly the farthest distance from its axis.
        reach = farthestFromAxis(balls[b], geometryInNearest, mover.axis);
      } else {
        // Along the chain by the triangle inequality; the first offset is fixed in this joint's
        // frame, so only its part perpendicular to the axis counts.
        const Eigen::Vector3d firstOffset = chainOrigin(robot, movers[k], movers[k - 1]).translation();
        reach = (firstOffset - firstOffset.dot(mover.axis) * mover.axis).norm() + outerChain + farthestFromNearest;
        outerChain += firstOffset.norm();
      }
      impl.jointReach(static_cast<Eigen::Index>(b), mover.joint) = reach;
      impl.movedBy(static_cast<Eigen::Index>(b), mover.joint) = true;
    }
  }
  for (auto* groups : {&impl.obstacleGroups, &impl.selfGroups}) {
    for (auto& group : *groups) {
      group.relativeReach = group.self ? relativeReach(impl, group.firstBody, group.secondBody)
                                       : Eigen::VectorXd(impl.jointReach.row(group.firstBody).transpose());
    }
  }
}

}  // namespace detail

const char* toString(MotionCheck method) {
  switch (method) {
    case MotionCheck::Discrete:
      return "discrete";
    case MotionCheck::Certified:
      return "certified";
  }
  return "?";
}

void validate(const MotionCheckOptions& options) {
  if (!(options.maxJointStep > 0.0) || !std::isfinite(options.maxJointStep)) {
    throw Error("motion check: maxJointStep must be a positive number of radians, got " +
                std::to_string(options.maxJointStep));
  }
  if (!(options.minimumClearance >= kSmallestMinimumClearance) || !std::isfinite(options.minimumClearance)) {
    throw Error("motion check: minimumClearance must be a finite distance >= 1e-5 m, got " +
                std::to_string(options.minimumClearance));
  }
}

bool isMotionCollisionFree(const CollisionModel& model, CollisionData& data, const robot::JointRef& qa,
                           const robot::JointRef& qb, double* lastValidFraction, const MotionCheckOptions& options) {
  checkJoints(model, qa, qb);
  validate(options);
  if (options.method == MotionCheck::Discrete) {
    return discreteMotionFree(model, data, qa, qb, lastValidFraction, options.maxJointStep);
  }
  return certifiedMotionFree(model, detail::workspaceOf(data), qa, qb, lastValidFraction, options.minimumClearance);
}

PathCertifier::PathCertifier(const CollisionModel& model, CollisionData& data, double minimumClearance)
    : model_(model), data_(data), minimumClearance_(minimumClearance) {
  validate(MotionCheckOptions{MotionCheck::Certified, 0.01, minimumClearance});
  budget_.resize(detail::implementationOf(model).groups.size());
  used_.resize(budget_.size());
  bound_.resize(budget_.size());
}

bool PathCertifier::anchorAll(const robot::JointRef& q) {
  const Implementation& impl = detail::implementationOf(model_);
  detail::updateRobot(model_, detail::workspaceOf(data_), q);
  ++measurements_;
  for (std::size_t k = 0; k < budget_.size(); ++k) {
    // The capsule bounds are taken as soon as they reach a few centimetres: enough for several waypoints.
    const PairMeasurement measured =
        measurePair(model_, detail::workspaceOf(data_), *impl.groups[k], 0.05, minimumClearance_);
    if (measured.tooClose) return false;
    budget_[k] = measured.gap;
    used_[k] = 0.0;
  }
  last_ = q;
  return true;
}

bool PathCertifier::start(const robot::JointRef& q) {
  checkJoints(model_, q, q);
  return anchorAll(q);
}

bool PathCertifier::extend(const robot::JointRef& q) {
  checkJoints(model_, last_, q);
  const Implementation& impl = detail::implementationOf(model_);
  step_ = (q - last_).cwiseAbs();
  bool remeasured = false;
  for (std::size_t k = 0; k < budget_.size(); ++k) {
    bound_[k] = impl.groups[k]->relativeReach.dot(step_);
    if (used_[k] + bound_[k] < budget_[k]) continue;
    // This pair's clearance at its anchor does not cover the motion: measure it again at the
    // motion's start (one forward kinematics for every pair that needs it).
    if (!remeasured) {
      detail::updateRobot(model_, detail::workspaceOf(data_), last_);
      ++measurements_;
      remeasured = true;
    }
    const PairMeasurement measured = measurePair(model_, detail::workspaceOf(data_), *impl.groups[k],
                                                 std::max(bound_[k], minimumClearance_), minimumClearance_);
    if (measured.tooClose) return false;
    budget_[k] = measured.gap;
    used_[k] = 0.0;
    if (bound_[k] >= budget_[k]) {
      // Not even this one motion: advance along it conservatively, then start afresh at its end.
      ++measurements_;
      if (!certifiedMotionFree(model_, detail::workspaceOf(data_), last_, q, nullptr, minimumClearance_)) return false;
      return anchorAll(q);
    }
  }
  for (std::size_t k = 0; k < budget_.size(); ++k) used_[k] += bound_[k];
  last_ = q;
  return true;
}

int discreteSegmentCount(const robot::JointRef& qa, const robot::JointRef& qb, double maxJointStep) {
  const double largestStep = qa.size() == 0 ? 0.0 : (qb - qa).cwiseAbs().maxCoeff();
  return std::max(1, static_cast<int>(std::ceil(largestStep / maxJointStep)));
}

double motionBound(const CollisionModel& model, int body, const robot::JointRef& qa, const robot::JointRef& qb) {
  checkJoints(model, qa, qb);
  checkBody(model, body);
  return detail::implementationOf(model).jointReach.row(body).transpose().dot((qb - qa).cwiseAbs());
}

double relativeMotionBound(const CollisionModel& model, int body, int otherBody, const robot::JointRef& qa,
                           const robot::JointRef& qb) {
  checkJoints(model, qa, qb);
  checkBody(model, body);
  checkBody(model, otherBody);
  return relativeReach(detail::implementationOf(model), body, otherBody).dot((qb - qa).cwiseAbs());
}

}  // namespace arcplan::collision
