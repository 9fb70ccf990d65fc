#pragma once
// OMPL glue: the joint space of a RobotModel as a RealVectorStateSpace, a state validity checker
// (collision + joint bounds, clearance from the distance query) and a motion validator that checks
// straight joint-space motions at a fixed maximum joint step. Any OMPL geometric planner can use
// the SpaceInformation from makeSpaceInformation; all three are safe to call from several threads.
#include <memory>
#include <utility>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include "arcplan/collision/collision_data_pool.h"
#include "arcplan/collision/collision_model.h"

namespace arcplan::collision {

// dof-dimensional RealVectorStateSpace, bounds = URDF joint limits, dimension names = joint names.
ompl::base::StateSpacePtr makeJointStateSpace(const robot::RobotModel& model);

class CollisionStateValidityChecker : public ompl::base::StateValidityChecker {
public:
  CollisionStateValidityChecker(ompl::base::SpaceInformation* si, std::shared_ptr<const CollisionModel> model);

  // Inside the joint bounds and collision-free.
  bool isValid(const ompl::base::State* state) const override;
  // Same, and `clearance` = the state's clearance().
  bool isValid(const ompl::base::State* state, double& clearance) const override;
  // Smallest robot–obstacle or robot–robot (non-allowed pair) distance [m]; 0 in collision.
  double clearance(const ompl::base::State* state) const override;

  const CollisionModel& model() const { return pool_.model(); }

private:
  CollisionDataPool pool_;
};

class JointMotionValidator : public ompl::base::MotionValidator {
public:
  // maxJointStep [rad]: no joint moves more than this between two checked states.
  JointMotionValidator(ompl::base::SpaceInformation* si, double maxJointStep);

  // s1 is taken as valid (OMPL's convention); s2 and the states in between are checked, in
  // bisection order so a blocked motion is usually rejected after a few checks.
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  // Checks from s1 toward s2 in order; on failure lastValid gets the last valid state (if
  // lastValid.first is not null) and its fraction of the motion.
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  double maxJointStep() const { return maxJointStep_; }
  // Number of segments the motion s1 -> s2 is split into (at least 1).
  int segmentCount(const ompl::base::State* s1, const ompl::base::State* s2) const;

private:
  double maxJointStep_;
};

// Joint state space + CollisionStateValidityChecker + JointMotionValidator, set up.
ompl::base::SpaceInformationPtr makeSpaceInformation(std::shared_ptr<const CollisionModel> model,
                                                     double maxJointStep = 0.01);

}  // namespace arcplan::collision
