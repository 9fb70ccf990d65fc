#pragma once
// The pieces of the certified motion check (motion_check.cpp) that PathCertifier (path_certifier.cpp) builds on:
// a pair group's lower bound in the current configuration and the whole-motion check it falls back to.
// Internal to arcplan::collision: not installed.
#include "arcplan/collision/collision_model.h"
#include "model_implementation.h"

namespace arcplan::collision::detail {

struct PairMeasurement {
  double gap;     // lower bound of the pair's distance [m]
  bool tooClose;  // an exact distance below minimumClearance
};

// The direction kept for part pair `pair` (Workspace::pairAxes) if found during the current motion (Workspace::motion),
// else zero, from now on kept for this motion: where a motion check measures depends on the motion alone.
Eigen::Vector3d& motionAxis(Workspace& data, int pair);

// A lower bound of group `groupIndex`'s (ModelImplementation::groups) distance in the current configuration
// (updateRobot): bounds where they reach `wanted` (minimumClearance plus what the caller will spend of it) or
// minimumClearance (the hulls' along a direction kept in the current motion, motionAxis), exact distances of the part
// pairs whose bounds are below; tooClose when an exact distance is below minimumClearance (the pair's m).
PairMeasurement measurePair(const CollisionModel& model, Workspace& data, std::size_t groupIndex, double wanted,
                            double minimumClearance);

// The certified check of the straight motion qa -> qb (motion_check.h, MotionCheck::Certified) without the
// argument checks; lastValidFraction as isMotionCollisionFree's.
bool certifiedMotionFree(const CollisionModel& model, CollisionData& workspace, const robot::JointRef& qa,
                         const robot::JointRef& qb, double* lastValidFraction, double minimumClearance);

}  // namespace arcplan::collision::detail
