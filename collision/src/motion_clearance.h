#pragma once
// What a certified motion check asks of minimumClearance m: one owner for the exact check
// (motion_check.cpp), its sphere prefilter (sphere_motion_check.cpp) and the approach zones
// (endpoint_clearance.cpp). When it accepts a motion is public: acceptanceMargin (motion_check.h).
// Internal to arcplan::collision: not installed.
#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/motion_check.h"

namespace arcplan::collision::detail {

// The smallest minimumClearance accepted: it must stay well above the exact distances' error (1e-6 m),
// or a pair just above it would certify (almost) no step.
inline constexpr double kSmallestMinimumClearance = 1e-5;

// The joint values of a motion's ends: dof each, finite. Throws arcplan::Error ("motion check: ...").
void checkJoints(const CollisionModel& model, const robot::JointRef& qa, const robot::JointRef& qb);

}  // namespace arcplan::collision::detail
