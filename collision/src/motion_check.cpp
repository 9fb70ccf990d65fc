// The certified motion check and the per-pair measurements it shares with PathCertifier (path_certifier.cpp):
// conservative advancement; the bounds themselves live in motion_bounds.cpp.
#include "arcplan/collision/motion_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "arcplan/common/error.h"
#include "model_implementation.h"
#include "certified_motion.h"
#include "motion_bounds.h"
#include "motion_clearance.h"
#include "sphere_prefilter.h"

namespace arcplan::collision {
namespace {

using detail::Implementation;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Exact distances are GJK's, which docs/collision.md measured exact to 1e-6 m; certificates take
// them this much smaller so they never rest on an overestimate.
constexpr double kDistanceSlack = 1e-6;
// A pair whose certificate runs out within this fraction of its last step after the front is
// measured again at the front already, so that one forward kinematics serves several pairs. On the
// long motions of perf/perf_collision.cpp 0 (only the pairs at the front) takes 1.8x the time of
// 0.5, 0.3–0.7 are within 7 % of it, 1 (every pair every time) takes 1.2x.
constexpr double kEarlyMeasurement = 0.5;
// States probed before advancing (probesClear): kProbes on motions at least kProbedLength long (Euclidean,
// rad), the midpoint alone on those at least kMidpointProbedLength. On RRTConnect's ~3 rad edges the three save
// more than they cost; on MBM's 0.3 rad random motions (perf CollisionMbmMotion) they cost more (median 0.22 ->
// 0.31 ms), but RRTConnect's 0.35 rad steps in the bookshelves at 1 cm (the mbm-ur5 suite) are mostly refused
// near a board, and the midpoint finds that before advancing does: 14 plans of 7 problems, same paths, 21.5 ->
// 18.1 s (thin 0047 -40 %, 0020 -18 %), none slower beyond noise; three probes there gave 19.2 s.
constexpr int kProbes = 3;
constexpr double kProbedLength = 1.0, kMidpointProbedLength = 0.2;
// Certificates keep minimumClearance m itself, each pair its own m_k = requiredDistance(self, m) (a self pair at
// most kSelfClearance, collision_model.h): a pair g apart stays at least m_k apart for (g − m_k)/rate; a pair
// measured closer than m_k + acceptanceMargin(m_k) rejects the motion (motion_check.h).
using detail::checkJoints;
using detail::kSmallestMinimumClearance;

// A lower bound of the group's distance in the current configuration (updateRobot): the capsule
// bounds when they reach `wanted` (minimumClearance plus what the caller will spend of it) or
// minimumClearance, else the hulls' bounds or the exact distances of the part pairs whose bounds are
// below. A bound between minimumClearance and `wanted` leaves PathCertifier too little to spend, and it
// falls back to a full certified check; refining such bounds instead (exact distances up to `wanted`)
// made its 1 cm walks on MBM 1.5x (capsules) to 6.6x (hulls too) slower. On arcplan's
// UR10e the capsules are tight enough that exact distances for larger bounds cost more (2.5 µs per
// GJK call) than the steps they save: below 2 cm they made the long motions of
// perf/perf_collision.cpp 2–2.4x slower.
}  // namespace

namespace detail {

Eigen::Vector3d& motionAxis(Workspace& data, int pair) {
  if (data.pairAxisMotions[pair] != data.motion) {  // a direction from an earlier query: not taken
    data.pairAxes[pair].setZero();
    data.pairAxisMotions[pair] = data.motion;
  }
  return data.pairAxes[pair];
}

PairMeasurement measurePair(const CollisionModel& model, Workspace& data, std::size_t groupIndex, double wanted,
                            double minimumClearance) {
  const Implementation& impl = detail::implementationOf(model);
  const Implementation::PairGroup& group = *impl.groups[groupIndex];
  if (group.rigid) return {group.rigidDistance - kDistanceSlack, group.rigidDistance < minimumClearance};
  double gap = std::max(detail::linkGap(impl, data, group), group.floor);
  if (gap >= wanted) return {gap, false};
  // Part pairs nearest first by their capsule bounds, so that the exact distances of the nearest
  // settle the group and the others are dismissed by their bounds (in the parts' order, a group of the
  // FTS300's or the Robotiq's many parts measured almost every hull).
  auto& order = data.partOrder;
  order.clear();
  for (std::size_t p = 0; p < group.parts.size(); ++p) {
    const auto [i, j] = group.parts[p];
    const double bound = detail::boundGap(impl, data, i, j, group.self);
    order.push_back({bound, bound, static_cast<int>(p)});
  }
  std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.key < b.key; });
  gap = std::max(gap, order.empty() ? kInfinity : order.front().key);
  if (gap >= minimumClearance) return {gap, false};
  double exact = kInfinity;
  for (const auto& [key, bound, p] : order) {
    // A part pair bounded above the smallest distance so far cannot lower it, and one bounded
    // above `wanted` certifies enough with its bound; so are all after it.
    if (bound >= std::min(wanted, exact)) {
      exact = std::min(exact, bound);
      break;
    }
    const auto [i, j] = group.parts[p];
    const auto &first = impl.robotParts[i], &second = detail::secondPart(impl, group, j);
    const Eigen::Isometry3d& secondPose = detail::secondPose(impl, data, group, j);
    // The hulls' lower bound (cheaper than the BVHs; along the direction kept in this motion, cheaper than GJK) will do
    // unless closer than minimumClearance.
    const double enough = std::min(minimumClearance, exact);
    Eigen::Vector3d& axis = motionAxis(data, impl.firstPartPair[groupIndex] + p);
    double hull = detail::hullGap(first, data.partPoses[i], second, secondPose, model.options(), enough, axis);
    if (hull < enough)  // then the containing mesh's bound (a primitive against a many-triangle mesh part)
      hull = std::max(hull, detail::containingMeshGap(first, data.partPoses[i], second, secondPose, model.options()));
    if (hull >= enough) {
      exact = std::min(exact, hull);
      continue;
    }
    const double d =
        detail::partsDistance(first, data.partPoses[i], second, secondPose, bound <= 0.0, model.options(), &axis);
    if (d < minimumClearance) return {d, true};
    exact = std::min(exact, d - kDistanceSlack);
  }
  return {std::max(gap, exact), false};
}

}  // namespace detail

namespace {

// The fraction of the motion over which a distance `gap` shrinking at most at `rate` stays positive.
double reachOf(double gap, double rate) {
  if (rate > 0.0) return gap / rate;
  return gap > 0.0 ? kInfinity : 0.0;
}

struct ReachRequest {
  double groupRate;              // the group's relativeReach · step
  const Eigen::VectorXd& delta;  // qb − qa
  const Eigen::VectorXd& step;   // |qb − qa|
  double wanted;                 // the reach that would certify the rest of the motion
  double minimumClearance;       // the motion's m (each pair keeps requiredDistance of it)
};

struct ReachMeasurement {
  double reach;   // the fraction of the motion, each way from the current state, over which the group is apart
  bool tooClose;  // an exact distance below minimumClearance + acceptanceMargin
};

// measurePair for the certified check, in fractions of the motion: each part pair's bound over its own
// rate (ModelImplementation::partPairReach), so a pair like the base and the upper arm, always a few centimetres apart
// near the shoulder, is not stepped at the speed of the elbow end (on RRTConnect's long MBM edges that pair alone set
// ~70 steps per motion). The part pairs with the smallest reach are refined first.
ReachMeasurement measureReach(const CollisionModel& model, detail::Workspace& data, int k,
                              const ReachRequest& request) {
  const Implementation& impl = detail::implementationOf(model);
  const Implementation::PairGroup& group = *impl.groups[k];
  const auto rateOf = [&](std::size_t p) {
    return impl.partPairReach.row(impl.firstPartPair[k] + static_cast<Eigen::Index>(p)).dot(request.step);
  };
  const double minimumClearance = group.required(request.minimumClearance);  // this pair's own m
  const double enough = minimumClearance + acceptanceMargin(minimumClearance);
  if (group.rigid) return {kInfinity, group.rigidDistance < enough};
  if (group.floor >= enough) return {kInfinity, false};  // it keeps `enough` everywhere
  const double linkGap = detail::linkGap(impl, data, group);
  const double linkReach = reachOf(linkGap - minimumClearance, request.groupRate);
  // Every bound taken instead of a distance is at least `enough`, so every reach is at least margin/rate.
  if (linkGap >= enough && linkReach >= request.wanted) return {linkReach, false};
  auto& order = data.partOrder;
  order.clear();
  double nearest = kInfinity, boundsReach = kInfinity;
  for (std::size_t p = 0; p < group.parts.size(); ++p) {
    const auto [i, j] = group.parts[p];
    const double bound = detail::boundGap(impl, data, i, j, group.self);
    nearest = std::min(nearest, bound);
    order.push_back({reachOf(bound - minimumClearance, rateOf(p)), bound, static_cast<int>(p)});
    boundsReach = std::min(boundsReach, order.back().key);
  }
  // A part pair's plane (motion_bounds.h) needs one body that stands still: an obstacle, or for a self pair the link
  // whose joints all move the other too (a serial arm's nearer link), in whose frame the other moves by the joints
  // between them alone. Links on two branches (a gripper's fingers) keep the distance over the rate.
  int mover = -2, still = -1;  // -2: not decided yet; -1: no plane
  detail::LinkVelocity velocity;
  double curvature = 0.0;
  const auto planes = [&] {
    if (mover == -2) {
      mover = -1;
      if (!group.self || detail::movesWith(impl, group.firstBody, group.secondBody)) {
        mover = group.firstBody;
        still = group.self ? group.secondBody : -1;
      } else if (detail::movesWith(impl, group.secondBody, group.firstBody)) {
        mover = group.secondBody;
        still = group.firstBody;
      }
      if (mover >= 0) {
        velocity = detail::linkVelocity(model.robot(), impl, mover, data.kinematics.linkPoses, request.delta, still);
        curvature = detail::linkCurvature(impl, mover, request.step, still);
      }
    }
    return mover >= 0;
  };
  // The plane of part pair p's bounding volumes, from the part that moves.
  const auto boundingPlaneReach = [&](int p) {
    const auto [i, j] = group.parts[p];
    const int moving = group.self && mover != group.firstBody ? j : i;
    const Eigen::Vector3d &start = data.capsuleStarts[moving], &end = data.capsuleEnds[moving];
    const double radius = impl.robotParts[moving].capsule.radius;
    detail::BoundingPlane plane;
    if (group.self) {
      const int other = moving == i ? j : i;
      plane = detail::capsulesPlane(start, end, radius, data.capsuleStarts[other], data.capsuleEnds[other],
                                    impl.robotParts[other].capsule.radius);
    } else if (const detail::Part& obstacle = impl.obstacleParts[j]; obstacle.boxBound) {
      plane = detail::capsuleBoxPlane(start, end, radius, impl.obstacleInversePoses[j], obstacle.boxHalfExtents);
    } else {
      plane = detail::capsulesPlane(start, end, radius, impl.obstacleCapsuleStarts[j], impl.obstacleCapsuleEnds[j],
                                    obstacle.capsule.radius);
    }
    return detail::capsulePlaneReach(start, end, radius, plane, velocity, curvature, minimumClearance);
  };
  if (std::max(linkGap, nearest) >= enough) {
    // Every part pair apart by its bounding volumes: where their distances over the rates would not certify the rest,
    // the bounding volumes' planes may (no exact distance: measuring one costs more than the steps it saves).
    double reach = boundsReach;
    if (std::max(linkReach, reach) < request.wanted && planes()) {
      reach = kInfinity;
      for (const auto& [key, bound, p] : order)
        reach = std::min(reach, key >= request.wanted ? key : std::max(key, boundingPlaneReach(p)));
    }
    return {std::max(linkReach, reach), false};
  }
  // Sorted only where the part pairs are refined (most measurements end above: 2.6 % of a bookshelf solve sorted).
  std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.key < b.key; });
  // A measured part pair's reach: its distance over its rate, or its hulls' plane's if longer.
  const auto measuredReach = [&](double gap, double rate, const detail::Part& first, const Eigen::Isometry3d& pose,
                                 const detail::Part& second, const Eigen::Isometry3d& secondPose,
                                 const Eigen::Vector3d& axis) {
    const double reach = reachOf(gap - minimumClearance, rate);
    if (!planes()) return reach;
    if (mover == group.firstBody) {
      return std::max(reach,
                      detail::planeReach(first, pose, second, secondPose, axis, velocity, curvature, minimumClearance));
    }
    // The second part moves: the same plane seen from it (its normal reversed, in the second part's frame).
    const Eigen::Vector3d reversed = secondPose.linear().transpose() * (pose.linear() * -axis);
    return std::max(
        reach, detail::planeReach(second, secondPose, first, pose, reversed, velocity, curvature, minimumClearance));
  };
  double best = kInfinity;
  for (const auto& [reach, bound, p] : order) {
    // A part pair bounded beyond `enough` that certifies enough, or no less than the best so far, keeps
    // its bound; the others are measured (a distance below `enough` rejects).
    if (bound >= enough) {
      // Its bounding volumes' plane first where their distance over the rate falls short (no GJK).
      double kept = reach;
      if (kept < std::min(request.wanted, best) && planes()) kept = std::max(kept, boundingPlaneReach(p));
      if (kept >= std::min(request.wanted, best)) {
        best = std::min(best, kept);
        continue;
      }
    }
    const auto [i, j] = group.parts[p];
    const auto &first = impl.robotParts[i], &second = detail::secondPart(impl, group, j);
    const Eigen::Isometry3d& secondPose = detail::secondPose(impl, data, group, j);
    const double rate = rateOf(p);
    Eigen::Vector3d& axis = detail::motionAxis(data, impl.firstPartPair[k] + p);
    const double hull = detail::hullGap(first, data.partPoses[i], second, secondPose, model.options(), enough, axis);
    if (hull >= enough) {
      best = std::min(best, measuredReach(hull, rate, first, data.partPoses[i], second, secondPose, axis));
      continue;
    }
    // Then the containing mesh's bound (a primitive against a many-triangle mesh part), taken as the hulls'.
    const double contained = detail::containingMeshGap(first, data.partPoses[i], second, secondPose, model.options());
    if (contained >= enough) {
      best = std::min(best, reachOf(contained - minimumClearance, rate));
      continue;
    }
    // A witness point inside `enough` rejects as the exact distance would (kWitnessSlack covers its error).
    if (detail::witnessCloser(first, data.partPoses[i], second, secondPose, enough - detail::kWitnessSlack))
      return {0.0, true};
    const double d =
        detail::partsDistance(first, data.partPoses[i], second, secondPose, bound <= 0.0, model.options(), &axis);
    if (d - kDistanceSlack < enough) return {0.0, true};
    best = std::min(best, measuredReach(d - kDistanceSlack, rate, first, data.partPoses[i], second, secondPose, axis));
  }
  return {std::max(linkReach, best), false};
}

// A few states of the motion, coarse to fine (its middle, then its quarters, ...), each asked whether
// it keeps minimumClearance: the certified check below would reject the motion at such a state too if it
// measured there, and a motion the spheres cannot settle is mostly one that collides or grazes an
// obstacle somewhere inside, which advancing from the ends finds only after many steps (on RRTConnect's
// long MBM edges 0.7–2.2 ms median).
bool probesClear(const CollisionModel& model, CollisionData& data, const robot::JointRef& qa, const robot::JointRef& qb,
                 double minimumClearance) {
  const double length = (qb - qa).norm();
  const int probes = length >= kProbedLength ? kProbes : length >= kMidpointProbedLength ? 1 : 0;
  robot::JointVector& q = detail::workspaceOf(data).probeJoints;
  int probed = 0;
  for (int parts = 2; probed < probes; parts *= 2) {
    for (int k = 1; k < parts && probed < probes; k += 2, ++probed) {
      q = qa + (static_cast<double>(k) / parts) * (qb - qa);
      if (!hasClearance(model, data, q, minimumClearance)) return false;
    }
  }
  return true;
}

// Conservative advancement from both ends, or only from the start when the last valid state is
// wanted. Pair k is proven to keep its own m_k (requiredDistance of minimumClearance) before
// motionPairs[k].certifiedFromStart and after certifiedFromEnd (open intervals: a pair at distance g at s keeps
// m_k on (s − (g − m_k)/rate, s + (g − m_k)/rate)); it is done when the two overlap. The front on each side is the
// smallest certificate of the pairs not done, and the pairs whose certificate ends there (or soon after) are measured
// there.
}  // namespace

bool detail::certifiedMotionFree(const CollisionModel& model, CollisionData& workspace, const robot::JointRef& qa,
                                 const robot::JointRef& qb, double* lastValidFraction, double minimumClearance) {
  const Implementation& impl = detail::implementationOf(model);
  detail::Workspace& data = detail::workspaceOf(workspace);
  // The sphere prefilter first: it certifies most motions with a few batches of 8 states. Where the last valid
  // state is wanted it defers no pair: the advancement of all pairs finds the same last state as without spheres.
  const bool bothEnds = lastValidFraction == nullptr;
  const detail::SphereMotion spheres = detail::sphereMotion(model, data, qa, qb, minimumClearance, bothEnds);
  if (spheres == detail::SphereMotion::Free) return true;
  if (spheres == detail::SphereMotion::Collides && bothEnds) return false;
  const bool pairsLeft = spheres == detail::SphereMotion::PairsLeft;
  // PairsLeft: per body whether the spheres left its obstacle pairs, then per self pair of the prefilter.
  const auto deferred = [&](int p) { return data.spheres->deferred[p] != 0; };
  const int bodies = pairsLeft ? impl.prefilter->tables().bodyCount : 0;
  bool obstaclesLeft = !pairsLeft;
  for (int b = 0; b < bodies; ++b) obstaclesLeft = obstaclesLeft || deferred(b);
  // Where only self pairs are left, the motion keeps its clearance from obstacles: nothing for the probes to find.
  if (bothEnds && obstaclesLeft && !probesClear(model, workspace, qa, qb, minimumClearance)) return false;
  ++data.motion;
  auto& pairs = data.motionPairs;
  // The pairs still to certify, in group order; a pair drops out once its certificates meet (on MBM ~400 groups,
  // most of them settled after the first measurement at each end, or by the spheres).
  auto& active = data.activePairs;
  active.clear();
  if (pairsLeft) {  // the spheres certified every pair but the deferred ones over the whole motion
    const detail::SpherePrefilter& prefilter = *impl.prefilter;
    for (int k = 0; k < static_cast<int>(impl.obstacleGroups.size()); ++k)
      if (deferred(impl.obstacleGroups[k].firstBody)) active.push_back(k);
    for (int p = bodies; p < prefilter.pairCount(); ++p)
      if (deferred(p))
        active.push_back(static_cast<int>(impl.obstacleGroups.size()) + prefilter.selfGroupOf(p - bodies));
  } else {
    for (int k = 0; k < static_cast<int>(pairs.size()); ++k) active.push_back(k);
  }
  const Eigen::VectorXd delta = qb - qa;
  const Eigen::VectorXd step = delta.cwiseAbs();
  for (const int k : active) pairs[k] = {impl.groups[k]->relativeReach.dot(step), 0.0, 1.0, 0.0, 1.0};
  const auto done = [&](int k) { return pairs[k].certifiedFromStart > pairs[k].certifiedFromEnd; };
  bool atStart = true;
  double lastClear = 0.0;  // the last start-side front measured clear
  while (true) {
    active.erase(std::remove_if(active.begin(), active.end(), done), active.end());
    if (active.empty()) return true;
    double front = kInfinity, back = -kInfinity;
    for (const int k : active) {
      front = std::min(front, pairs[k].certifiedFromStart);
      back = std::max(back, pairs[k].certifiedFromEnd);
    }
    const double s = atStart ? front : back;
    data.motionJoints = qa + s * (qb - qa);
    detail::updateRobot(model, data, data.motionJoints);
    for (const int k : active) {
      auto& pair = pairs[k];
      const double ahead = atStart ? pair.certifiedFromStart - s : s - pair.certifiedFromEnd;
      const double lastStep =
          atStart ? pair.certifiedFromStart - pair.measuredFromStart : pair.measuredFromEnd - pair.certifiedFromEnd;
      if (ahead > kEarlyMeasurement * lastStep) continue;
      const double remaining = atStart ? pair.certifiedFromEnd - s : s - pair.certifiedFromStart;
      const ReachMeasurement measured =
          measureReach(model, data, k, {pair.rate, delta, step, remaining, minimumClearance});
      if (measured.tooClose) {
        if (lastValidFraction != nullptr) *lastValidFraction = lastClear;
        return false;
      }
      const double reach = measured.reach;
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

namespace {

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
  return detail::certifiedMotionFree(model, data, qa, qb, lastValidFraction, options.minimumClearance);
}

namespace {

// What a certified motion at minimumClearance accepts of a pair at a measured state: its own m and the margin.
double acceptedDistance(bool self, double minimumClearance) {
  const double m = requiredDistance(self, minimumClearance);
  return m + acceptanceMargin(m);
}

// The minimumClearance of a query about what a certified motion accepts (`query` names it in the error).
void checkMinimumClearance(const char* query, double minimumClearance) {
  if (!(minimumClearance > 0.0) || !std::isfinite(minimumClearance)) {
    throw Error(std::string(query) + ": minimumClearance must be a finite distance > 0 m, got " +
                std::to_string(minimumClearance));
  }
}

}  // namespace

bool keepsAcceptanceMargin(const CollisionModel& model, CollisionData& data, const robot::JointRef& q,
                           double minimumClearance) {
  checkMinimumClearance("acceptance margin query", minimumClearance);
  return detail::keepsDistances(model, data, q, acceptedDistance(false, minimumClearance),
                                acceptedDistance(true, minimumClearance));
}

Shortfall smallestShortfall(const CollisionModel& model, CollisionData& data, const robot::JointRef& q,
                            double minimumClearance) {
  checkMinimumClearance("shortfall query", minimumClearance);
  const detail::LeastPair least = detail::leastOffsetPair(model, data, q, acceptedDistance(false, minimumClearance),
                                                          acceptedDistance(true, minimumClearance));
  Shortfall result;
  if (least.group == nullptr) return result;
  result.self = least.group->self;
  result.pair = detail::namesOf(model, *least.group);
  result.distance = least.distance;
  result.shortfall = least.value;
  return result;
}

int discreteSegmentCount(const robot::JointRef& qa, const robot::JointRef& qb, double maxJointStep) {
  const double largestStep = qa.size() == 0 ? 0.0 : (qb - qa).cwiseAbs().maxCoeff();
  return std::max(1, static_cast<int>(std::ceil(largestStep / maxJointStep)));
}

}  // namespace arcplan::collision
