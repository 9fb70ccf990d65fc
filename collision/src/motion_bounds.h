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

}  // namespace arcplan::collision
