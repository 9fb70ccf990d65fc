#pragma once
// OMPL glue: the joint space of a RobotModel as a RealVectorStateSpace, a state validity checker
// (collision + joint bounds, clearance from the distance query) and a motion validator for straight
// joint-space motions (certified by default, see motion_check.h). Any OMPL geometric planner can use
// the SpaceInformation from makeSpaceInformation; all three are safe to call from several threads.
//
// A clearance c > 0 (a benchmark suite's `clearance`, docs/benchmarks.md) makes every planner keep
// the same distance: a state is valid only if the robot is at least c from every obstacle and every
// non-allowed pair of its own bodies at least min(c, kSelfClearance) apart (requiredDistance,
// collision_model.h), and certified motions reject pairs measured closer than that.
// Given the problem's endpoints, a start or goal closer than c (plus the certified check's acceptance
// margin) relaxes c in its approach zone (endpoint_clearance.h): the one rule every planner of a problem sees.
#include <memory>
#include <utility>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include "arcplan/collision/collision_data_pool.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/endpoint_clearance.h"
#include "arcplan/collision/motion_check.h"

namespace arcplan::collision {

namespace detail {
template <typename Answer, int Parts>
class AnswerMemo;   // collision/src/answer_memo.h
struct MotionMemo;  // collision/src/answer_memo.h
}  // namespace detail

// dof-dimensional RealVectorStateSpace, bounds = URDF joint limits, dimension names = joint names.
ompl::base::StateSpacePtr makeJointStateSpace(const robot::RobotModel& model);

class CollisionStateValidityChecker : public ompl::base::StateValidityChecker {
public:
  // Throws arcplan::Error for a negative or non-finite clearance.
  CollisionStateValidityChecker(ompl::base::SpaceInformation* si, std::shared_ptr<const CollisionModel> model,
                                double clearance = 0.0);
  // The clearance each state keeps from `required` (stateClearanceAt); throws arcplan::Error when null.
  CollisionStateValidityChecker(ompl::base::SpaceInformation* si, std::shared_ptr<const CollisionModel> model,
                                std::shared_ptr<const EndpointClearance> required);

  // Inside the joint bounds, collision-free and (required clearance r > 0 at the state) every pair at
  // least requiredDistance(self, r) apart.
  bool isValid(const ompl::base::State* state) const override;
  // Same, and `clearance` = the state's clearance().
  bool isValid(const ompl::base::State* state, double& clearance) const override;
  // The largest clearance the state meets (clearanceOf: the robot–obstacle distance, or a non-allowed self
  // pair's distance where that is below kSelfClearance) [m]; 0 in collision.
  double clearance(const ompl::base::State* state) const override;

  const CollisionModel& model() const { return pool_.model(); }
  const EndpointClearance& requiredClearance() const { return *required_; }

private:
  CollisionDataPool pool_;
  std::shared_ptr<const EndpointClearance> required_;
  std::shared_ptr<detail::AnswerMemo<bool, 1>> valid_;  // the states found valid (isValid answers them at once)
};

class JointMotionValidator : public ompl::base::MotionValidator {
public:
  // Checks motions with isMotionCollisionFree(model, ..., options); throws arcplan::Error for
  // options out of range, or a `required` whose motionClearance() is below the check's 1e-5 m. With `required`, the
  // motion is checked piece by piece (required->motionPieces), each with its piece's clearance as minimumClearance
  // instead of options.minimumClearance.
  JointMotionValidator(ompl::base::SpaceInformation* si, std::shared_ptr<const CollisionModel> model,
                       MotionCheckOptions options = {}, std::shared_ptr<const EndpointClearance> required = nullptr);

  // s1 is taken as valid (OMPL's convention, though the certified check measures it as well); s2
  // must be valid (si->isValid, exact) and the motion collision-free. Both overloads remember their answers and give
  // a motion asked before (the same joint values bit for bit) its answer then, at once (collision/src/answer_memo.h).
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  // Checks from s1 toward s2; on failure lastValid gets the last valid state (if lastValid.first is
  // not null) and its fraction of the motion, in [0, 1) (0 when s2 is outside the joint bounds).
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  const MotionCheckOptions& options() const { return options_; }
  double maxJointStep() const { return options_.maxJointStep; }
  // Number of segments a discrete check splits the motion s1 -> s2 into (at least 1).
  int segmentCount(const ompl::base::State* s1, const ompl::base::State* s2) const;

private:
  // isMotionCollisionFree with options_, or with `required`, on each of its motionPieces at that piece's clearance.
  bool motionFree(const robot::JointRef& q1, const robot::JointRef& q2, double* lastValidFraction) const;

  CollisionDataPool pool_;
  MotionCheckOptions options_;
  std::shared_ptr<const EndpointClearance> required_;
  std::shared_ptr<detail::MotionMemo> memo_;  // each overload's answers (checkMotion answers them at once)
};

// Joint state space + CollisionStateValidityChecker + JointMotionValidator, set up. The
// SpaceInformation's state validity checking resolution (what OMPL planners treat as the longest
// motion checked in one piece) is OMPL's default for certified motions and maxJointStep for discrete ones.
// With clearance > 0 the state validity checker keeps it and the certified motion check rejects pairs
// closer than max(clearance, motionCheck.minimumClearance); `endpoints` (the problem's start and goal)
// get approach zones where they are closer than that themselves (EndpointClearance, shared by both).
ompl::base::SpaceInformationPtr makeSpaceInformation(std::shared_ptr<const CollisionModel> model,
                                                     const MotionCheckOptions& motionCheck = {}, double clearance = 0.0,
                                                     const std::vector<robot::JointVector>& endpoints = {});

}  // namespace arcplan::collision
