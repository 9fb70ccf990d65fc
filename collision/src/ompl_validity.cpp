#include "arcplan/collision/ompl_validity.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "arcplan/common/error.h"

namespace arcplan::collision {
namespace {

namespace ob = ompl::base;

Eigen::Map<const Eigen::VectorXd> jointsOf(const ob::State* state, int dof) {
  return {state->as<ob::RealVectorStateSpace::StateType>()->values, dof};
}

}  // namespace

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
                                                             std::shared_ptr<const CollisionModel> model)
    : ob::StateValidityChecker(si), pool_(std::move(model)) {
  specs_.clearanceComputationType = ob::StateValidityCheckerSpecs::APPROXIMATE;  // workspace distance, not C-space
}

bool CollisionStateValidityChecker::isValid(const ob::State* state) const {
  if (!si_->satisfiesBounds(state)) return false;
  const auto lease = pool_.lease();
  return isCollisionFree(model(), *lease, jointsOf(state, model().robot().dof()));
}

bool CollisionStateValidityChecker::isValid(const ob::State* state, double& clearance) const {
  clearance = this->clearance(state);
  return clearance > 0.0 && si_->satisfiesBounds(state);
}

double CollisionStateValidityChecker::clearance(const ob::State* state) const {
  const auto lease = pool_.lease();
  return distance(model(), *lease, jointsOf(state, model().robot().dof())).minimum();
}

JointMotionValidator::JointMotionValidator(ob::SpaceInformation* si, double maxJointStep)
    : ob::MotionValidator(si), maxJointStep_(maxJointStep) {
  if (!(maxJointStep > 0.0)) throw Error("joint motion validator: maxJointStep must be positive");
}

int JointMotionValidator::segmentCount(const ob::State* s1, const ob::State* s2) const {
  const auto* a = s1->as<ob::RealVectorStateSpace::StateType>()->values;
  const auto* b = s2->as<ob::RealVectorStateSpace::StateType>()->values;
  double largestStep = 0.0;
  for (unsigned j = 0; j < si_->getStateDimension(); ++j) largestStep = std::max(largestStep, std::abs(b[j] - a[j]));
  return std::max(1, static_cast<int>(std::ceil(largestStep / maxJointStep_)));
}

bool JointMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  if (!si_->isValid(s2)) {
    ++invalid_;
    return false;
  }
  const int segments = segmentCount(s1, s2);
  bool valid = true;
  if (segments > 1) {
    ob::State* test = si_->allocState();
    std::queue<std::pair<int, int>> intervals;  // ranges of intermediate states still to check
    intervals.emplace(1, segments - 1);
    while (valid && !intervals.empty()) {
      const auto [first, last] = intervals.front();
      intervals.pop();
      const int middle = (first + last) / 2;
      si_->getStateSpace()->interpolate(s1, s2, static_cast<double>(middle) / segments, test);
      valid = si_->isValid(test);
      if (first < middle) intervals.emplace(first, middle - 1);
      if (middle < last) intervals.emplace(middle + 1, last);
    }
    si_->freeState(test);
  }
  valid ? ++valid_ : ++invalid_;
  return valid;
}

bool JointMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                       std::pair<ob::State*, double>& lastValid) const {
  const int segments = segmentCount(s1, s2);
  ob::State* test = si_->allocState();
  bool valid = true;
  int step = 1;
  for (; step <= segments; ++step) {
    const ob::State* checked = s2;
    if (step < segments) {
      si_->getStateSpace()->interpolate(s1, s2, static_cast<double>(step) / segments, test);
      checked = test;
    }
    if (!si_->isValid(checked)) {
      valid = false;
      break;
    }
  }
  si_->freeState(test);
  if (valid) {
    ++valid_;
    return true;
  }
  lastValid.second = static_cast<double>(step - 1) / segments;
  if (lastValid.first != nullptr) si_->getStateSpace()->interpolate(s1, s2, lastValid.second, lastValid.first);
  ++invalid_;
  return false;
}

ob::SpaceInformationPtr makeSpaceInformation(std::shared_ptr<const CollisionModel> model, double maxJointStep) {
  if (!model) throw Error("makeSpaceInformation: no collision model");
  auto space = makeJointStateSpace(model->robot());
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(std::make_shared<CollisionStateValidityChecker>(si.get(), std::move(model)));
  si->setMotionValidator(std::make_shared<JointMotionValidator>(si.get(), maxJointStep));
  // Only used by code that asks SpaceInformation for its resolution; the motion validator above
  // works with maxJointStep directly.
  si->setStateValidityCheckingResolution(std::min(1.0, maxJointStep / space->getMaximumExtent()));
  si->setup();
  return si;
}

}  // namespace arcplan::collision
