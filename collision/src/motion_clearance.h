#pragma once
// What a certified motion check asks of minimumClearance m and when it accepts a motion: one owner for
// the exact check (motion_check.cpp), its sphere prefilter (sphere_motion_check.cpp) and the approach
// zones (endpoint_clearance.cpp), so the spheres never accept a motion the exact check would reject.
// Internal to arcplan::collision: not installed.
#include <algorithm>

#include "arcplan/collision/collision_model.h"

namespace arcplan::collision::detail {

// The smallest minimumClearance accepted: it must stay well above the exact distances' error (1e-6 m),
// or a pair just above it would certify (almost) no step.
inline constexpr double kSmallestMinimumClearance = 1e-5;

// A pair measured closer than m + acceptanceMargin(m) rejects the motion, so every step advances by at
// least margin/rate: a quarter of m, at most 0.5 mm, which a motion that keeps m + 2 mm between samples
// 1 mm apart still passes.
inline double acceptanceMargin(double minimumClearance) { return std::min(0.25 * minimumClearance, 5e-4); }

// The joint values of a motion's ends: dof each, finite. Throws arcplan::Error ("motion check: ...").
void checkJoints(const CollisionModel& model, const robot::JointRef& qa, const robot::JointRef& qb);

}  // namespace arcplan::collision::detail
