#include "arcplan/collision/ompl_validity.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "arcplan/collision/joint_states.h"
#include "arcplan/common/error.h"
#include "motion_clearance.h"
#include "answer_memo.h"

namespace arcplan::collision {

namespace ob = ompl::base;

ob::StateSpacePtr makeJointStateSpace(const robot::RobotModel& model) {
  auto space = std::make_shared<ob::RealVectorStateSpace>(static_cast<unsigned>(model.dof()));
  ob::RealVectorBounds bounds(static_cast<unsigned>(model.dof()));
  for (int j = 0; j < model.dof(); ++j) {
    bounds.setLow(static_cast<unsigned>(j), model.joints()[j].limits.lower);
    bounds.setHigh(static_cast<unsigned>(j), model.joints()[j].limits.upper);
    space->setDimensionName(static_cast<unsigned>(j), model.joints()[j].name);
  }
  space->setBounds(bounds);
  space->setName(model.name() + "_joints");
  return space;
}

CollisionStateValidityChecker::CollisionStateValidityChecker(ob::SpaceInformation* si,
                                                             std::shared_ptr<const CollisionModel> model,
                                                             double clearance)
    : CollisionStateValidityChecker(si, std::move(model), std::make_shared<const EndpointClearance>(clearance)) {}

CollisionStateValidityChecker::CollisionStateValidityChecker(ob::SpaceInformation* si,
                                                             std::shared_ptr<const CollisionModel> model,
                                                             std::shared_ptr<const EndpointClearance> required)
    : ob::StateValidityChecker(si),
      pool_(std::move(model)),
      required_(std::move(required)),
      valid_(std::make_shared<detail::AnswerMemo<bool, 1>>()) {
  if (!required_) throw Error("state validity: no required clearance");
  specs_.clearanceComputationType = ob::StateValidityCheckerSpecs::APPROXIMATE;  // workspace distance, not C-space
}

bool CollisionStateValidityChecker::isValid(const ob::State* state) const {
  if (!si_->satisfiesBounds(state)) return false;
  const auto q = jointsOf(state, model().robot().dof());
  const robot::JointRef joints(q);
  if (valid_->find({&joints})) return true;
  const auto lease = pool_.lease();
  const double required = required_->stateClearanceAt(q);
  const bool valid = required > 0.0 ? hasClearance(model(), *lease, q, required) : isCollisionFree(model(), *lease, q);
  // Only the valid ones: most invalid states are random samples, never asked again.
  if (valid) valid_->insert({&joints}, true);
  return valid;
}

bool CollisionStateValidityChecker::isValid(const ob::State* state, double& clearance) const {
  clearance = this->clearance(state);
  return clearance > 0.0 && si_->satisfiesBounds(state) &&
         clearance >= required_->stateClearanceAt(jointsOf(state, model().robot().dof()));
}

double CollisionStateValidityChecker::clearance(const ob::State* state) const {
  const auto lease = pool_.lease();
  return clearanceOf(distance(model(), *lease, jointsOf(state, model().robot().dof())));
}

JointMotionValidator::JointMotionValidator(ob::SpaceInformation* si, std::shared_ptr<const CollisionModel> model,
                                           MotionCheckOptions options,
                                           std::shared_ptr<const EndpointClearance> required)
    : ob::MotionValidator(si),
      pool_(std::move(model)),
      options_(options),
      required_(std::move(required)),
      memo_(std::make_shared<detail::MotionMemo>()) {
  validate(options_);
  // motionFree certifies pieces with the clearances of `required` in place of options.minimumClearance;
  // checked here, as options are, so that nothing throws from inside OMPL's checkMotion. A zone's
  // clearance is never below the floor (endpoint_clearance.cpp), so motionClearance() is the smallest.
  if (required_ && !(required_->motionClearance() >= detail::kSmallestMinimumClearance)) {
    throw Error("motion validator: the required motion clearance must be at least " +
                std::to_string(detail::kSmallestMinimumClearance) + " m (the motion check's floor), got " +
                std::to_string(required_->motionClearance()));
  }
}

bool JointMotionValidator::motionFree(const robot::JointRef& q1, const robot::JointRef& q2,
                                      double* lastValidFraction) const {
  const auto lease = pool_.lease();
  if (!required_) return isMotionCollisionFree(pool_.model(), *lease, q1, q2, lastValidFraction, options_);
  // Piece by piece with what each part must keep: certifying the whole motion with the smallest
  // clearance of the zones it touches let states far from the zone keep only the zone's clearance, and
  // OMPL's simplifier makes waypoints of such states (MBM bookshelf_thin: paths that touched a shelf).
  const robot::JointVector delta = q2 - q1;
  const auto at = [&](double s) -> robot::JointVector { return s == 1.0 ? robot::JointVector(q2) : q1 + s * delta; };
  for (const MotionPiece& piece : required_->motionPieces(q1, q2)) {
    MotionCheckOptions options = options_;
    options.minimumClearance = piece.clearance;
    double fraction = 0.0;
    if (!isMotionCollisionFree(pool_.model(), *lease, at(piece.from), at(piece.to),
                               lastValidFraction != nullptr ? &fraction : nullptr, options)) {
      if (lastValidFraction != nullptr) *lastValidFraction = piece.from + fraction * (piece.to - piece.from);
      return false;
    }
  }
  return true;
}

int JointMotionValidator::segmentCount(const ob::State* s1, const ob::State* s2) const {
  const int dof = pool_.model().robot().dof();
  return discreteSegmentCount(jointsOf(s1, dof), jointsOf(s2, dof), options_.maxJointStep);
}

bool JointMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  const int dof = pool_.model().robot().dof();
  const robot::JointRef from(jointsOf(s1, dof)), to(jointsOf(s2, dof));
  std::optional<detail::MotionAnswer> answer = memo_->plain.find({&from, &to});
  if (!answer) {
    answer = detail::MotionAnswer{si_->isValid(s2) && motionFree(from, to, nullptr)};
    memo_->plain.insert({&from, &to}, *answer);
  }
  answer->valid ? ++valid_ : ++invalid_;
  return answer->valid;
}

bool JointMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                       std::pair<ob::State*, double>& lastValid) const {
  const int dof = pool_.model().robot().dof();
  const robot::JointRef from(jointsOf(s1, dof)), to(jointsOf(s2, dof));
  std::optional<detail::MotionAnswer> answer = memo_->traced.find({&from, &to});
  if (!answer) {
    // Both checks below cover the collisions of s2; the joint bounds are the rest of its validity (a
    // straight motion between states inside the bounds stays inside).
    answer = detail::MotionAnswer{si_->satisfiesBounds(s2), 0.0};
    if (answer->valid) answer->valid = motionFree(from, to, &answer->lastValidFraction);
    memo_->traced.insert({&from, &to}, *answer);
  }
  if (answer->valid) {
    ++valid_;
    return true;
  }
  lastValid.second = answer->lastValidFraction;
  if (lastValid.first != nullptr) si_->getStateSpace()->interpolate(s1, s2, answer->lastValidFraction, lastValid.first);
  ++invalid_;
  return false;
}

ob::SpaceInformationPtr makeSpaceInformation(std::shared_ptr<const CollisionModel> model,
                                             const MotionCheckOptions& motionCheck, double clearance,
                                             const std::vector<robot::JointVector>& endpoints) {
  if (!model) throw Error("makeSpaceInformation: no collision model");
  validate(motionCheck);
  auto space = makeJointStateSpace(model->robot());
  auto si = std::make_shared<ob::SpaceInformation>(space);
  const auto required =
      std::make_shared<const EndpointClearance>(*model, clearance, motionCheck.minimumClearance, endpoints);
  si->setStateValidityChecker(std::make_shared<CollisionStateValidityChecker>(si.get(), model, required));
  MotionCheckOptions motions = motionCheck;
  motions.minimumClearance = required->motionClearance();
  si->setMotionValidator(std::make_shared<JointMotionValidator>(si.get(), std::move(model), motions, required));
  // The resolution is what OMPL planners take as the longest motion worth checking in one piece
  // (BiTRRT, for one, connects its trees only within 10 of them). Only the discrete validator checks
  // at its step; with certified motions OMPL's default (1 % of the space's extent) stands.
  if (motionCheck.method == MotionCheck::Discrete) {
    si->setStateValidityCheckingResolution(std::min(1.0, motionCheck.maxJointStep / space->getMaximumExtent()));
  }
  si->setup();
  return si;
}

}  // namespace arcplan::collision
