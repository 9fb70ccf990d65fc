#pragma once
// Collision checks of many states at once: the same answers as isCollisionFree state by state,
// computed 8 states per SIMD batch by the sphere prefilter (docs/collision.md); only states whose
// spheres it cannot clear go to FCL one by one.
#include <vector>

#include <Eigen/Core>

#include "arcplan/collision/collision_model.h"

namespace arcplan::collision {

// free[k] = isCollisionFree(model, data, states.col(k)); states has robot().dof() rows, one column
// per state. Throws arcplan::Error for a wrong row count.
void areCollisionFree(const CollisionModel& model, CollisionData& data, const Eigen::Ref<const Eigen::MatrixXd>& states,
                      std::vector<bool>& free);

}  // namespace arcplan::collision
