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

// chordMotionBound from the link's poses at the two ends (`from`, `to`, in any one frame) and the motion's joint
// steps |qb − qa|. A point x of the link moves along p(s), s in [0, 1]; on a straight joint motion of a revolute chain
// ∂²p/∂q_i∂q_j = ω_i × (ω_j × (p − o_j)) for joint i before j, so |p''| ≤ K = Σ_i Σ_j |Δq_i||Δq_j| D_later(i,j), D_j
// the link's reach about joint j (jointReach), and p'(s) differs from the chord p(1) − p(0) = ∫ p'(t) dt by at most ∫ K
// |s − t| dt ≤ K/2. The chord is at most the move of the centre of the link's bounding ball plus its radius times ‖R_to
// − R_from‖ = 2 sin(θ/2), θ the link's turn: B = C + K/2. Between waypoints 1 cm of TCP apart a link moves about 1 cm,
// where Σ_j |Δq_j|·D_j, into which every joint's full reach enters, is 3–5 cm.
double chordRate(const ModelImplementation& impl, int body, const Eigen::Isometry3d& from, const Eigen::Isometry3d& to,
                 const robot::JointRef& step);

}  // namespace detail

}  // namespace arcplan::collision
