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

// What a pair must keep all along a motion for the exact check to surely accept it, whichever states it measures:
// it rejects a pair it measures closer than m + acceptanceMargin(m) (motion_check.h) and measures distances to
// 1e-6 m, so 10 µm more than that is measured clear by it everywhere. A certificate to this (the spheres', a floor
// grid's) answers as the exact check would.
inline double keptClearance(double minimumClearance) {
  return minimumClearance + acceptanceMargin(minimumClearance) + 1e-5;
}

// The joint values of a motion's ends: dof each, finite. Throws arcplan::Error ("motion check: ...").
void checkJoints(const CollisionModel& model, const robot::JointRef& qa, const robot::JointRef& qb);

}  // namespace arcplan::collision::detail
