#pragma once
// Shared helpers of the planner tests: the thesis scenes as OMPL problems, solving with a planner
// from the registry, and reading a solution back as joints and TCP poses.
#include <ompl/geometric/PathGeometric.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/joint_states.h"
#include "arcplan/collision/scene.h"
#include "arcplan/planners/planning_problem.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/pose.h"

namespace arcplan::testing {

inline std::filesystem::path sceneFile(const std::string& name) {
  return std::filesystem::path(ARCPLAN_TEST_DATA_DIR) / "scenes" / (name + ".yaml");
}

inline std::shared_ptr<const collision::Scene> loadTestScene(const std::string& name) {
  return std::make_shared<const collision::Scene>(collision::loadScene(sceneFile(name)));
}

inline planners::PlanningProblem thesisProblem(const std::string& sceneName) {
  return planners::makePlanningProblem(loadTestScene(sceneName));
}

// Sets up `planner` (registry name) with parameters on the problem and solves it.
inline std::pair<ompl::base::PlannerPtr, ompl::base::PlannerStatus> solve(
    planners::PlanningProblem& problem, const std::string& planner,
    const std::vector<std::pair<std::string, std::string>>& parameters = {}, double time = 5.0) {
  problem.setup->clear();
  auto instance =
      planners::makePlanner(planner, problem.setup->getSpaceInformation(), problem.plannerContext(), parameters);
  problem.setup->setPlanner(instance);
  problem.setup->setup();
  const auto status = problem.setup->solve(time);
  return {instance, status};
}

inline std::vector<Eigen::Isometry3d> tcpPoses(const std::vector<robot::Vector6>& joints) {
  std::vector<Eigen::Isometry3d> poses;
  for (const auto& q : joints) poses.push_back(robot::tipPose(robot::ur10e(), q));
  return poses;
}

// The thesis' tool orientation (rpy 0, -pi, pi/2): tool z straight down.
inline Eigen::Matrix3d thesisToolDown() { return robot::rotationFromRpy(0.0, -M_PI, M_PI_2); }

inline const Eigen::Vector3d& thesisA() {
  static const Eigen::Vector3d a(0.4, -0.4, 0.25);
  return a;
}
inline const Eigen::Vector3d& thesisB() {
  static const Eigen::Vector3d b(0.5, 0.4, 0.46);
  return b;
}

// Smallest robot distance (obstacles and self) along a joint path, every motion sampled at 2 mrad:
// a second measurement, independent of the certified check the planner used.
inline double closestApproach(const planners::PlanningProblem& problem, const std::vector<robot::Vector6>& joints) {
  collision::CollisionData data(*problem.collisionModel);
  double closest = INFINITY;
  for (std::size_t i = 1; i < joints.size(); ++i) {
    const int samples = static_cast<int>(std::ceil((joints[i] - joints[i - 1]).cwiseAbs().maxCoeff() / 2e-3)) + 1;
    for (int k = 0; k <= samples; ++k) {
      const robot::Vector6 q = joints[i - 1] + (joints[i] - joints[i - 1]) * (double(k) / samples);
      closest = std::min(closest, collision::distance(*problem.collisionModel, data, q).minimum());
    }
  }
  return closest;
}

// The same along the problem's solution path.
inline double closestApproach(const planners::PlanningProblem& problem) {
  return closestApproach(problem, collision::waypointsOf(problem.setup->getSolutionPath()));
}

}  // namespace arcplan::testing
