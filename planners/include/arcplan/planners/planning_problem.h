#pragma once
// A scene query as an OMPL problem: joint state space from the URDF limits, validity from collision
// checking, start and goal joint states from the query's endpoints.
//
// An endpoint given as joints is used as given (checked: 6 finite values inside the limits, no
// collision). An endpoint given as a tool0 pose is solved with the analytic IK: with a `seed`, the
// in-limit solution nearest to the seed (it must be collision-free: the seed chooses the arm
// posture, so no other posture is substituted); without one, the collision-free solution nearest
// to kDefaultIkSeed, the upright "elbow up, wrist down" posture.
//
// Randomness: OMPL's sampling planners draw from ompl::RNG, whose seed is process-global and takes
// effect only if set (ompl::RNG::setSeed) before the first RNG is created — i.e. before any planner,
// sampler or SimpleSetup exists. It can be set once per process; `arcplan plan --seed` does so first.
#include <ompl/geometric/SimpleSetup.h>

#include <memory>
#include <string>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/collision/scene.h"
#include "arcplan/planners/planner_registry.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::planners {

// (0, -pi/2, pi/2, -pi/2, -pi/2, 0): upper arm up, forearm forward, tool pointing down.
extern const robot::Vector6 kDefaultIkSeed;

struct PlanningProblemOptions {
  collision::MotionCheckOptions motionCheck;  // how the SpaceInformation's motion validator checks motions
  double clearance = 0.0;  // m every state and motion keeps (collision::makeSpaceInformation); 0: only no contact
};

struct PlanningProblem {
  std::shared_ptr<const collision::Scene> scene;
  std::string queryName;
  std::shared_ptr<const collision::CollisionModel> collisionModel;
  std::shared_ptr<ompl::geometric::SimpleSetup> setup;  // start and goal set, no planner yet
  robot::Vector6 start = robot::Vector6::Zero();
  robot::Vector6 goal = robot::Vector6::Zero();

  PlannerContext plannerContext() const { return {collisionModel, scene->obstacles}; }
};

// Throws arcplan::Error naming the scene file, query and endpoint: unknown query, unreachable pose,
// no in-limit or collision-free solution, joints out of limits or in collision (with the pair).
PlanningProblem makePlanningProblem(std::shared_ptr<const collision::Scene> scene, const std::string& queryName = "",
                                    const PlanningProblemOptions& options = {});

// The joint configuration of one endpoint (rules above); `label` names it in messages ("start of query A_to_B").
robot::Vector6 resolveEndpoint(const collision::QueryEndpoint& endpoint, const collision::CollisionModel& model,
                               const robot::UrInverseKinematics& ik, const std::string& label);

}  // namespace arcplan::planners
