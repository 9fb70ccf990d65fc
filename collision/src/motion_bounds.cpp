// The motion bounds of the certified check (motion_check.h, docs/collision.md): per body and joint how
// far the body's points are from the joint's axis, per body pair and per part pair how fast their
// distance can shrink on a straight joint motion.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"
#include "model_implementation.h"
#include "motion_bounds.h"
#include "motion_clearance.h"

namespace arcplan::collision {
namespace {

using detail::Implementation;

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

// Per joint, a bound of the distance from its axis of every point of geometry `balls` on link `link`,
// in every configuration (0 for the joints that do not move it).
Eigen::VectorXd axisReach(const robot::RobotModel& robot, int link, const std::vector<BoundingBall>& balls) {
  Eigen::VectorXd reach = Eigen::VectorXd::Zero(robot.dof());
  // The moving links from the body's link toward the base: movers[0] is the nearest one.
  std::vector<int> movers;
  for (int l = link; l >= 0; l = robot.links()[l].parent) {
    if (robot.links()[l].joint >= 0) movers.push_back(l);
  }
  if (movers.empty()) return reach;
  // Geometry in the frame of the nearest moving link (through fixed joints only).
  const Eigen::Isometry3d geometryInNearest =
      link == movers[0] ? Eigen::Isometry3d::Identity() : chainOrigin(robot, movers[0], link);
  const double farthestFromNearest = farthestDistance(balls, geometryInNearest);
  // Between moving links the offsets are rigid: |o_next − o_previous| never changes.
  double outerChain = 0.0;  // |o_movers[0] − o_movers[1]| + ... + |o_movers[k-2] − o_movers[k-1]|
  for (std::size_t k = 0; k < movers.size(); ++k) {
    const robot::Link& mover = robot.links()[movers[k]];
    if (k == 0) {
      // Rigidly attached to the joint's own link: exactly the farthest distance from its axis.
      reach[mover.joint] = farthestFromAxis(balls, geometryInNearest, mover.axis);
    } else {
      // Along the chain by the triangle inequality; the first offset is fixed in this joint's
      // frame, so only its part perpendicular to the axis counts.
      const Eigen::Vector3d firstOffset = chainOrigin(robot, movers[k], movers[k - 1]).translation();
      reach[mover.joint] =
          (firstOffset - firstOffset.dot(mover.axis) * mover.axis).norm() + outerChain + farthestFromNearest;
      outerChain += firstOffset.norm();
    }
  }
  return reach;
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

// A link's pose in the frame of its rigid root, the nearest link at or above it that its own joint turns
// (or the chain base): links with the same root never move against each other.
struct RigidFrame {
  int root;
  Eigen::Isometry3d pose;
};

RigidFrame rigidFrame(const robot::RobotModel& robot, int link) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  while (robot.links()[link].joint < 0 && robot.links()[link].parent >= 0) {
    pose = robot.links()[link].originInParent * pose;
    link = robot.links()[link].parent;
  }
  return {link, pose};
}

// Pivot points closer to a joint's axis than this [m] count as on it (the 2× slack below covers them).
constexpr double kOnAxis = 1e-9;

// Turning `joint` by δ turns everything beyond it about its axis; seen from a body the joint does not
// move, it is the same relative motion as turning that body by −δ about the axis while the rest stays.
// The distance between a part beyond the joint and a part of that body then changes by at most how far
// the body part's points are from the axis times |δ|, whatever the other joints are:
// - where the body is rigid with the joint's parent link the axis is fixed in the body's frame: the
//   farthest point from the axis (MBM's base against the upper arm's end cap next to it change their
//   distance at the base's radius per radian of the shoulder pan, not the cap's);
// - else, where the axis passes through a point that the joints between the body and the joint do not
//   move (it lies on their axes: a UR shoulder frame's origin on the base joint's axis), the farthest
//   point from that pivot (the base against the upper arm's tube per radian of the shoulder lift: 0.14
//   instead of the tube's far end at 0.36 m). A pivot e off an intermediate axis moves by at most 2e.
// -1 when neither holds (another branch of the tree).
double fixedSideReach(const robot::RobotModel& robot, int bodyLink, int joint, const std::vector<BoundingBall>& balls) {
  const int mover = robot.joints()[joint].link;
  int parent = robot.links()[mover].parent;
  if (parent < 0) return -1.0;
  const RigidFrame body = rigidFrame(robot, bodyLink);
  RigidFrame frame = rigidFrame(robot, parent);
  if (body.root == frame.root) {
    // The mover's frame before its rotation (its axis passes through its origin), in the body's frame.
    const Eigen::Isometry3d moverInBody = body.pose.inverse() * frame.pose * robot.links()[mover].originInParent;
    return farthestFromAxis(balls, moverInBody.inverse(), robot.links()[mover].axis);
  }
  // The point of the joint's axis nearest to the next turning axis up the chain (where they cross on a UR
  // arm), carried up at zero angles to the body's rigid root.
  const Eigen::Isometry3d moverInFrame = frame.pose * robot.links()[mover].originInParent;
  Eigen::Vector3d pivot = moverInFrame.translation();
  const Eigen::Vector3d direction = moverInFrame.linear() * robot.links()[mover].axis;
  const Eigen::Vector3d& next = robot.links()[frame.root].axis;
  const double along = direction.dot(next), denominator = 1.0 - along * along;
  if (denominator > 1e-12) pivot -= ((pivot.dot(direction) - along * pivot.dot(next)) / denominator) * direction;
  double slack = 0.0;
  while (frame.root != body.root) {
    const robot::Link& turning = robot.links()[frame.root];
    if (turning.parent < 0) return -1.0;  // not below the body: another branch
    slack += 2.0 * (pivot - pivot.dot(turning.axis) * turning.axis).norm();
    if (!(slack <= kOnAxis)) return -1.0;
    pivot = turning.originInParent * pivot;
    frame = rigidFrame(robot, turning.parent);
    pivot = frame.pose * pivot;
  }
  pivot = body.pose.inverse() * pivot;
  double farthest = 0.0;
  for (const auto& ball : balls) farthest = std::max(farthest, (ball.center - pivot).norm() + ball.radius);
  return farthest + slack;
}

void checkBody(const CollisionModel& model, int body) {
  if (body < 0 || body >= static_cast<int>(model.linkNames().size())) {
    throw Error("motion bound: link index " + std::to_string(body) + " is not one of the " +
                std::to_string(model.linkNames().size()) + " links with collision geometry");
  }
}

}  // namespace

namespace detail {

void checkJoints(const CollisionModel& model, const robot::JointRef& qa, const robot::JointRef& qb) {
  if (qa.size() != model.robot().dof() || qb.size() != model.robot().dof()) {
    throw Error("motion check: expected " + std::to_string(model.robot().dof()) + " joint values per end, got " +
                std::to_string(qa.size()) + " and " + std::to_string(qb.size()));
  }
  if (!qa.allFinite() || !qb.allFinite()) throw Error("motion check: joint values must be finite numbers");
}

double chordRate(const Implementation& impl, int body, const Eigen::Isometry3d& from, const Eigen::Isometry3d& to,
                 const robot::JointRef& step) {
  // What the double-precision poses may be off by, on the chord and on the turn's square root near zero [m].
  constexpr double kRoundingSlack = 1e-7;
  const Capsule& capsule = impl.linkCapsules[static_cast<std::size_t>(body)];
  const Eigen::Vector3d centre = 0.5 * (capsule.start + capsule.end);
  const double radius = 0.5 * (capsule.end - capsule.start).norm() + capsule.radius;
  const double turn = std::sqrt(std::max(0.0, 3.0 - (from.linear().transpose() * to.linear()).trace()));
  const double chord = (to * centre - from * centre).norm() + turn * radius;
  return chord + 0.5 * linkCurvature(impl, body, step) + kRoundingSlack;
}

bool movesWith(const Implementation& impl, int body, int other) {
  for (Eigen::Index j = 0; j < impl.movedBy.cols(); ++j)
    if (impl.movedBy(other, j) && !impl.movedBy(body, j)) return false;
  return true;
}

double linkCurvature(const Implementation& impl, int body, const robot::JointRef& step, int still) {
  // Σ_j D_j |Δq_j| (|Δq_j| + 2 Σ_{i<j} |Δq_i|) over the joints that move the link, base first (RobotModel keeps a
  // chain's joints in that order, so j is the later of each pair). Relative to `still`, the chain from `still` to
  // `body`: the same sum over the joints between them.
  double curvature = 0.0, earlier = 0.0;
  for (Eigen::Index j = 0; j < step.size(); ++j) {
    if (!impl.movedBy(body, j) || (still >= 0 && impl.movedBy(still, j))) continue;
    curvature += impl.jointReach(body, j) * step[j] * (step[j] + 2.0 * earlier);
    earlier += step[j];
  }
  return curvature;
}

LinkVelocity linkVelocity(const robot::RobotModel& robot, const Implementation& impl, int body,
                          const std::vector<Eigen::Isometry3d>& linkPoses, const robot::JointRef& delta, int still) {
  LinkVelocity velocity;
  // A link's frame turns about its joint's axis (given in that frame) through its own origin.
  for (int l = impl.linkCapsuleLink[static_cast<std::size_t>(body)]; l >= 0; l = robot.links()[l].parent) {
    const int joint = robot.links()[l].joint;
    if (joint < 0 || delta[joint] == 0.0 || (still >= 0 && impl.movedBy(still, joint))) continue;
    const Eigen::Vector3d axis = linkPoses[l].linear() * robot.links()[l].axis;
    velocity.angular += delta[joint] * axis;
    velocity.linear += delta[joint] * linkPoses[l].translation().cross(axis);
  }
  return velocity;
}

namespace {

// The Δ each way over which points starting `room` short of a plane, approaching it at rates `towards` (forward) and
// `away` (backward) at most at the measured state and at most `curvature`·|t − s| faster elsewhere, stay short of it:
// rate·Δ + curvature·Δ²/2 = room, in the form that stays accurate where curvature is small.
double reachBeforePlane(double room, double towards, double away, double curvature) {
  // Rounding of the rate's products of poses and joint steps (~1e-15 of metres per unit of the motion).
  constexpr double kRateSlack = 1e-9;
  if (!(room > 0.0)) return 0.0;
  const double rate = std::max({towards, away, 0.0}) + kRateSlack;
  if (!std::isfinite(rate)) return 0.0;
  return 2.0 * room / (rate + std::sqrt(rate * rate + 2.0 * curvature * room));
}

}  // namespace

double planeReach(const Part& part, const Eigen::Isometry3d& pose, const Part& obstacle,
                  const Eigen::Isometry3d& obstaclePose, const Eigen::Vector3d& axis, const LinkVelocity& velocity,
                  double curvature, double minimumClearance) {
  if (axis.isZero()) return 0.0;
  const double room = separatingGap(part, pose, obstacle, obstaclePose, axis) - kHullDistanceSlack - minimumClearance;
  const Eigen::Vector3d normal = pose.linear() * axis;
  const Eigen::Vector3d across = normal.cross(velocity.angular);  // n·(ω × p) = p·(n × ω)
  const Eigen::Vector3d acrossInPart = pose.linear().transpose() * across;
  const double offset = pose.translation().dot(across) + normal.dot(velocity.linear);
  return reachBeforePlane(room, detail::supportAlong(part, acrossInPart) + offset,
                          detail::supportAlong(part, -acrossInPart) - offset, curvature);
}

BoundingPlane capsulesPlane(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius,
                            const Eigen::Vector3d& otherStart, const Eigen::Vector3d& otherEnd, double otherRadius) {
  const auto [onFirst, onOther] = segmentClosestPoints(start, end, otherStart, otherEnd);
  const Eigen::Vector3d between = onOther - onFirst;
  const double length = between.norm();
  if (!(length > radius + otherRadius)) return {};
  // Rounding of the closest points and their distance (~1e-16 m) is far below the slack taken off.
  return {between / length, length - radius - otherRadius - kHullDistanceSlack};
}

BoundingPlane capsuleBoxPlane(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius,
                              const Eigen::Isometry3d& toBox, const Eigen::Vector3d& halfExtents) {
  const CapsuleBoxGaps gaps = capsuleBoxGaps(toBox * start, toBox * end, radius, halfExtents);
  // Towards the box: down from beyond its upper face, up from below its lower one; 0 where they overlap.
  const Eigen::Vector3d apart = gaps.gap.cwiseMax(0.0);
  const Eigen::Vector3d towards = gaps.aboveUpperFace.select(-apart, apart);
  const double gap = towards.norm();
  if (!(gap > kHullDistanceSlack)) return {};
  return {toBox.linear().transpose() * (towards / gap), gap - kHullDistanceSlack};
}

double capsulePlaneReach(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius,
                         const BoundingPlane& plane, const LinkVelocity& velocity, double curvature,
                         double minimumClearance) {
  if (!(plane.gap > 0.0)) return 0.0;
  const Eigen::Vector3d across = plane.normal.cross(velocity.angular);
  const double offset = plane.normal.dot(velocity.linear);
  const double atStart = start.dot(across) + offset, atEnd = end.dot(across) + offset;
  const double round = radius * across.norm();
  return reachBeforePlane(plane.gap - minimumClearance, std::max(atStart, atEnd) + round,
                          std::max(-atStart, -atEnd) + round, curvature);
}

void computeMotionBounds(const robot::RobotModel& robot, Implementation& impl) {
  const std::size_t bodies = impl.linkCapsules.size();
  std::vector<std::vector<BoundingBall>> balls(bodies), partBalls(impl.robotParts.size());
  for (std::size_t i = 0; i < impl.robotParts.size(); ++i) {
    const Part& part = impl.robotParts[i];
    if (part.hullPoints.empty()) {
      partBalls[i].push_back({part.offset * part.capsule.start, part.capsule.radius});
      partBalls[i].push_back({part.offset * part.capsule.end, part.capsule.radius});
    }
    for (const auto& point : part.hullPoints) partBalls[i].push_back({part.offset * point, 0.0});
    balls[part.body].insert(balls[part.body].end(), partBalls[i].begin(), partBalls[i].end());
  }
  impl.jointReach = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(bodies), robot.dof());
  impl.movedBy.setConstant(static_cast<Eigen::Index>(bodies), robot.dof(), false);
  for (std::size_t b = 0; b < bodies; ++b) {
    const int link = impl.linkCapsuleLink[b];
    impl.jointReach.row(static_cast<Eigen::Index>(b)) = axisReach(robot, link, balls[b]).transpose();
    for (int l = link; l >= 0; l = robot.links()[l].parent) {
      if (robot.links()[l].joint >= 0) impl.movedBy(static_cast<Eigen::Index>(b), robot.links()[l].joint) = true;
    }
  }
  // The same per part pair, with the parts' own reaches, which near a joint axis are far below their body's.
  Eigen::MatrixXd partReach(static_cast<Eigen::Index>(impl.robotParts.size()), robot.dof());
  for (std::size_t i = 0; i < impl.robotParts.size(); ++i) {
    partReach.row(static_cast<Eigen::Index>(i)) =
        axisReach(robot, impl.linkCapsuleLink[impl.robotParts[i].body], partBalls[i]).transpose();
  }
  impl.partPairReach = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(impl.partPairs.size()), robot.dof());
  for (std::size_t p = 0; p < impl.partPairs.size(); ++p) {
    const auto& [group, i, j] = impl.partPairs[p];
    for (int joint = 0; joint < robot.dof(); ++joint) {
      const bool first = impl.movedBy(group->firstBody, joint);
      const bool second = group->self && impl.movedBy(group->secondBody, joint);
      if (first == second) continue;
      double reach = first ? partReach(i, joint) : partReach(j, joint);
      if (group->self) {
        // The part the joint does not move, where the joint's axis is fixed in its frame (fixedSideReach).
        const int still = first ? j : i;
        const double other =
            fixedSideReach(robot, impl.linkCapsuleLink[impl.robotParts[still].body], joint, partBalls[still]);
        if (other >= 0.0) reach = std::min(reach, other);
      }
      impl.partPairReach(static_cast<Eigen::Index>(p), joint) = reach;
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

double motionBound(const CollisionModel& model, int body, const robot::JointRef& qa, const robot::JointRef& qb) {
  detail::checkJoints(model, qa, qb);
  checkBody(model, body);
  return detail::implementationOf(model).jointReach.row(body).transpose().dot((qb - qa).cwiseAbs());
}

double relativeMotionBound(const CollisionModel& model, int body, int otherBody, const robot::JointRef& qa,
                           const robot::JointRef& qb) {
  detail::checkJoints(model, qa, qb);
  checkBody(model, body);
  checkBody(model, otherBody);
  return relativeReach(detail::implementationOf(model), body, otherBody).dot((qb - qa).cwiseAbs());
}

double chordMotionBound(const CollisionModel& model, int body, const robot::JointRef& qa, const robot::JointRef& qb) {
  detail::checkJoints(model, qa, qb);
  checkBody(model, body);
  const detail::Implementation& impl = detail::implementationOf(model);
  robot::KinematicsData atA(model.robot()), atB(model.robot());
  robot::forwardKinematics(model.robot(), qa, atA);
  robot::forwardKinematics(model.robot(), qb, atB);
  const int link = impl.linkCapsuleLink[static_cast<std::size_t>(body)];
  return detail::chordRate(impl, body, atA.linkPoses[link], atB.linkPoses[link], (qb - qa).cwiseAbs());
}

}  // namespace arcplan::collision
