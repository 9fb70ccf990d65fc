#include "arcplan/planners/planning_problem.h"

#include <ompl/base/ScopedState.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arcplan/collision/joint_states.h"
#include "arcplan/collision/ompl_validity.h"
#include "arcplan/common/error.h"
#include "arcplan/robot/joint_limits.h"
#include "arcplan/robot/pose.h"

namespace arcplan::planners {

const robot::Vector6 kDefaultIkSeed = (robot::Vector6() << 0.0, -M_PI_2, M_PI_2, -M_PI_2, -M_PI_2, 0.0).finished();

namespace {

std::string jointText(const robot::Vector6& q) {
  std::ostringstream text;
  text << "[";
  for (int j = 0; j < 6; ++j) text << (j ? ", " : "") << q[j];
  text << "]";
  return text.str();
}

}  // namespace

robot::Vector6 resolveEndpoint(const collision::QueryEndpoint& endpoint, const collision::CollisionModel& model,
                               const robot::UrInverseKinematics& ik, const std::string& label) {
  const robot::RobotModel& robotModel = model.robot();
  collision::CollisionData data(model);
  if (endpoint.joints) {
    const robot::Vector6& q = *endpoint.joints;
    if (const auto j = robot::firstJointOutsideLimits(robotModel, q))
      throw Error(label + ": " + robot::outsideLimitsText(robotModel, *j, q[*j], "joint " + std::to_string(*j)));
    const collision::CollisionReport report = collision::collide(model, data, q);
    if (!report.valid)
      throw Error(label + ": the joint configuration is in collision (" + collision::describeCollisions(report) + ")");
    return q;
  }
  if (!endpoint.pose) throw Error(label + ": needs `pose` or `joints`");
  const Eigen::Isometry3d pose = robot::poseFromXyzRpy(*endpoint.pose);
  std::vector<robot::Vector6> solutions = ik.solveAll(pose);
  if (solutions.empty()) {
    throw Error(label + ": the pose is out of reach or every IK solution is outside the joint limits");
  }
  if (endpoint.seed) {
    const robot::Vector6 q = *ik.solveNearest(pose, *endpoint.seed);
    const collision::CollisionReport report = collision::collide(model, data, q);
    if (!report.valid) {
      throw Error(label + ": the IK solution nearest to the seed, " + jointText(q) + ", is in collision (" +
                  collision::describeCollisions(report) + "); choose another seed");
    }
    return q;
  }
  std::sort(solutions.begin(), solutions.end(), [](const robot::Vector6& x, const robot::Vector6& y) {
    return (x - kDefaultIkSeed).squaredNorm() < (y - kDefaultIkSeed).squaredNorm();
  });
  for (const robot::Vector6& q : solutions) {
    if (collision::isCollisionFree(model, data, q)) return q;
  }
  throw Error(label + ": every one of the " + std::to_string(solutions.size()) + " IK solutions is in collision");
}

PlanningProblem makePlanningProblem(std::shared_ptr<const collision::Scene> scene, const std::string& queryName,
                                    const PlanningProblemOptions& options) {
  if (!scene) throw Error("planning problem: no scene");
  PlanningProblem problem;
  problem.scene = scene;
  const collision::Query& query = scene->query(queryName);
  problem.queryName = query.name;
  problem.collisionModel = collision::makeCollisionModel(*scene);
  const robot::UrInverseKinematics ik(problem.collisionModel->robot());
  const std::string where = "scene " + scene->sourceFile.string() + ", query '" + query.name + "'";
  problem.start = resolveEndpoint(query.start, *problem.collisionModel, ik, where + ", start");
  problem.goal = resolveEndpoint(query.goal, *problem.collisionModel, ik, where + ", goal");

  problem.setup = std::make_shared<ompl::geometric::SimpleSetup>(
      collision::makeSpaceInformation(problem.collisionModel, options.motionCheck, options.clearance,
                                      {problem.start, problem.goal}));  // approach zones (endpoint_clearance.h)
  const ompl::base::StateSpacePtr& space = problem.setup->getStateSpace();
  ompl::base::ScopedState<> start(space), goal(space);
  collision::setJoints(start.get(), problem.start);
  collision::setJoints(goal.get(), problem.goal);
  problem.setup->setStartAndGoalStates(start, goal);
  return problem;
}

}  // namespace arcplan::planners
