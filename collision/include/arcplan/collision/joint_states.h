#pragma once
// Joint vectors <-> states of arcplan's OMPL joint state space (makeJointStateSpace in
// ompl_validity.h: a RealVectorStateSpace with one dimension per joint, in chain order). The one
// place that knows how a state stores the joints.
#include <vector>

#include <Eigen/Core>
#include <ompl/base/State.h>
#include <ompl/geometric/PathGeometric.h>

#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::collision {

// The `dof` joints of a state, without a copy.
Eigen::Map<const Eigen::VectorXd> jointsOf(const ompl::base::State* state, int dof);
// Writes q (one value per dimension of the state) into the state.
void setJoints(ompl::base::State* state, const robot::JointRef& q);
// The waypoints of a path in the 6-joint state space of a UR arm; throws arcplan::Error naming the
// dimension when the path's space does not have 6.
std::vector<robot::Vector6> waypointsOf(const ompl::geometric::PathGeometric& path);

}  // namespace arcplan::collision
