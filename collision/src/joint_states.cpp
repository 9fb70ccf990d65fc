#include "arcplan/collision/joint_states.h"

#include <string>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "arcplan/common/error.h"

namespace arcplan::collision {

namespace ob = ompl::base;

Eigen::Map<const Eigen::VectorXd> jointsOf(const ob::State* state, int dof) {
  return {state->as<ob::RealVectorStateSpace::StateType>()->values, dof};
}

void setJoints(ob::State* state, const robot::JointRef& q) {
  Eigen::Map<Eigen::VectorXd>(state->as<ob::RealVectorStateSpace::StateType>()->values, q.size()) = q;
}

std::vector<robot::Vector6> waypointsOf(const ompl::geometric::PathGeometric& path) {
  const unsigned dimension = path.getSpaceInformation()->getStateDimension();
  if (dimension != 6) {
    throw Error("expected a path of a 6-joint arm, got a state space of dimension " + std::to_string(dimension));
  }
  std::vector<robot::Vector6> waypoints;
  waypoints.reserve(path.getStateCount());
  for (std::size_t i = 0; i < path.getStateCount(); ++i) waypoints.emplace_back(jointsOf(path.getState(i), 6));
  return waypoints;
}

}  // namespace arcplan::collision
