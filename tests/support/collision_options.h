#pragma once
// The collision model with FCL alone (no sphere prefilter, no hull layers): the reference the layered
// answers are compared with in the collision tests.
#include "arcplan/collision/collision_model.h"

namespace arcplan::testing {

inline collision::CollisionModelOptions exactOnly() {
  collision::CollisionModelOptions options;
  options.spherePrefilter = false;
  options.hullLayer = false;
  return options;
}

}  // namespace arcplan::testing
