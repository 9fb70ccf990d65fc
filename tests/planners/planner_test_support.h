#pragma once
// Shared helpers of the planner tests: the thesis scenes as OMPL problems, solving with a planner
// from the registry, and reading a solution back as joints and TCP poses.
#include <ompl/geometric/PathGeometric.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

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

}  // namespace arcplan::testing
