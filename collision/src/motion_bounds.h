#pragma once
// The bounds the certified motion check relies on (motion_check.h), exposed for the tests that
// check them against sampled motions. Internal to arcplan::collision: not installed.
#include "arcplan/collision/collision_model.h"

namespace arcplan::collision {

// For links given by their index into model.linkNames() [m]: how far any point of link `body` can
// move on the motion qa -> qb (in base_link), and by how much the distance between links `body`
// and `otherBody` can change (in the frame of their nearest common ancestor, the points of each
// together move at most this far). Throw arcplan::Error for a bad index or joint count.
double motionBound(const CollisionModel& model, int body, const robot::JointRef& qa, const robot::JointRef& qb);
double relativeMotionBound(const CollisionModel& model, int body, int otherBody, const robot::JointRef& qa,
                           const robot::JointRef& qb);
// A rate B of link `body` on the straight motion qa -> qb taken from its poses at the two ends: no point of the link
// moves faster than B per unit of the motion's fraction anywhere on it, as motionBound's Σ_j |Δq_j|·D_j, but near
// what the link moves rather than what every joint's full reach could (detail::chordRate). Throws arcplan::Error as
// above.
double chordMotionBound(const CollisionModel& model, int body, const robot::JointRef& qa, const robot::JointRef& qb);

namespace detail {

struct ModelImplementation;
struct Part;

// chordMotionBound from the link's poses at the two ends (`from`, `to`, in any one frame) and the motion's joint
// steps |qb − qa|. A point x of the link moves along p(s), s in [0, 1]; on a straight joint motion of a revolute chain
// ∂²p/∂q_i∂q_j = ω_i × (ω_j × (p − o_j)) for joint i before j, so |p''| ≤ K = Σ_i Σ_j |Δq_i||Δq_j| D_later(i,j), D_j
// the link's reach about joint j (jointReach), and p'(s) differs from the chord p(1) − p(0) = ∫ p'(t) dt by at most ∫ K
// |s − t| dt ≤ K/2. The chord is at most the move of the centre of the link's bounding ball plus its radius times ‖R_to
// − R_from‖ = 2 sin(θ/2), θ the link's turn: B = C + K/2. Between waypoints 1 cm of TCP apart a link moves about 1 cm,
// where Σ_j |Δq_j|·D_j, into which every joint's full reach enters, is 3–5 cm.
double chordRate(const ModelImplementation& impl, int body, const Eigen::Isometry3d& from, const Eigen::Isometry3d& to,
                 const robot::JointRef& step);

// Whether every joint that moves link `other` moves link `body` too (`other` nearer the base on the same chain, or
// moved by no joint): then `body` moves in `other`'s frame by the joints that move it and not `other` alone.
bool movesWith(const ModelImplementation& impl, int body, int other);

// K of chordRate: |d²p/ds²| <= K for every point p of link `body` anywhere on a straight motion with joint steps `step`
// (|qb − qa|), s the motion's fraction. With `still` (a link `body` movesWith), the same for `body`'s points in
// `still`'s frame: the joints that move `still` are left out.
double linkCurvature(const ModelImplementation& impl, int body, const robot::JointRef& step, int still = -1);

// How the points of link `body` move at one configuration of a straight motion with joint steps `delta` (qb − qa,
// signed): dp/ds = angular × p + linear for every point p fixed to the link, in the frame of `linkPoses` (forward
// kinematics of that configuration, base link frame). Revolute joints: Σ_j Δq_j ω_j × (p − o_j), ω_j and o_j the axis
// and origin of each joint that moves the link. With `still` (a link `body` movesWith), the velocity relative to
// `still`'s points: the joints that move both move both alike and are left out.
struct LinkVelocity {
  Eigen::Vector3d angular = Eigen::Vector3d::Zero(), linear = Eigen::Vector3d::Zero();
};
LinkVelocity linkVelocity(const robot::RobotModel& robot, const ModelImplementation& impl, int body,
                          const std::vector<Eigen::Isometry3d>& linkPoses, const robot::JointRef& delta,
                          int still = -1);

// How far, in fractions of a straight motion, robot part `part` (at `pose`, one configuration of the motion) stays more
// than `minimumClearance` from obstacle part `obstacle` each way from that configuration, from the plane between
// them with normal `axis` (unit, in the part's frame, towards the obstacle: the direction GJK found; 0 for a zero
// axis): everything of the obstacle lies at least G beyond the part's hull along it (separatingGap). The part's points
// move along the normal at a rate of at most B = max_p |n·p'(s)| at that configuration (p' = angular × p + linear of
// `velocity`, linear in p: its extremes over the part are the hull's support along n × angular) and of at most
// B + K·|t − s| anywhere else on the motion (K = `curvature`, linkCurvature), so the part keeps more than m from the
// plane, hence from the obstacle, while B·Δ + K·Δ²/2 < G − m. Where the part slides along the obstacle (a gripper over
// a shelf's board) B is far below the rate of every joint's full reach, which bounds how fast the part moves in any
// direction. `obstacle` stands still: an obstacle part, or for a self pair a part of the link the other movesWith, with
// `velocity` and `curvature` relative to that link.
double planeReach(const Part& part, const Eigen::Isometry3d& pose, const Part& obstacle,
                  const Eigen::Isometry3d& obstaclePose, const Eigen::Vector3d& axis, const LinkVelocity& velocity,
                  double curvature, double minimumClearance);
// A plane between two bounding volumes: what stands still lies at least `gap` beyond the moving one along the unit
// `normal` (base link frame, pointing from the moving one to the other); gap 0 where none was found.
struct BoundingPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double gap = 0.0;
};
// Between two capsules (segments and radii, base link frame): through their segments' closest points.
BoundingPlane capsulesPlane(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius,
                            const Eigen::Vector3d& otherStart, const Eigen::Vector3d& otherEnd, double otherRadius);
// Between a capsule and a box centred at its frame's origin (`toBox`: base link frame to box frame): between the
// capsule's bounding box in the box frame and the box, whose gaps per axis point from one to the other
// (capsuleBoxLowerBound's bound).
BoundingPlane capsuleBoxPlane(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius,
                              const Eigen::Isometry3d& toBox, const Eigen::Vector3d& halfExtents);
// planeReach for a part inside the capsule `start`–`end` with radius `radius` (base link frame), `plane` away from what
// stands still: where no exact distance was measured, from the bounding volumes' plane.
double capsulePlaneReach(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius,
                         const BoundingPlane& plane, const LinkVelocity& velocity, double curvature,
                         double minimumClearance);

}  // namespace detail

}  // namespace arcplan::collision
