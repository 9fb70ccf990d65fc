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
#include "arcplan/planners/arc_planner.h"
#include "arcplan/planners/planner_registry.h"
#include "arcplan/planners/planning_problem.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/pose.h"
#include "support/obstacles.h"

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

// Sets up `planner` (registry name) with parameters on the problem and solves it. The arc planner's
// search runs without its wall-clock deadline unless one is given: these tests check what the search
// finds, which must not depend on the machine's load (the deadline has its own tests).
inline std::pair<ompl::base::PlannerPtr, ompl::base::PlannerStatus> solve(
    planners::PlanningProblem& problem, const std::string& planner,
    std::vector<std::pair<std::string, std::string>> parameters = {}, double time = 5.0) {
  problem.setup->clear();
  const bool deadlineGiven = std::any_of(parameters.begin(), parameters.end(),
                                         [](const auto& parameter) { return parameter.first == "deadline"; });
  if (planners::isArcPlanner(planner) && !deadlineGiven) parameters.emplace_back("deadline", "0");
  auto instance =
      planners::makePlanner(planner, problem.setup->getSpaceInformation(), problem.plannerContext(), parameters);
  problem.setup->setPlanner(instance);
  problem.setup->setup();
  const auto status = problem.setup->solve(time);
  return {instance, status};
}

// A shelf unit (back, two sides, bottom, middle and top panels, 2 cm thick, turned -59 degrees about z)
// between start and goal on thesis_free's table, from the generated suite (shelf-003), start and goal
// given as joints: a via-point search of dozens of routes.
inline planners::PlanningProblem shelfProblem() {
  auto scene = std::make_shared<collision::Scene>(*loadTestScene("thesis_free"));
  const Eigen::Matrix3d yaw = Eigen::AngleAxisd(-1.03088228752451, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const double depth = 0.310129750493969, width = 0.409913369894675, height = 0.555941355155275;
  const auto panel = [&](const std::string& name, const Eigen::Vector3d& centre, const Eigen::Vector3d& size) {
    auto obstacle = box(name, centre, size);
    obstacle.pose.linear() = yaw;
    return obstacle;
  };
  scene->obstacles.push_back(
      panel("shelf_back", {0.593562317513646, 0.204946690382173, 0.277970677577637}, {0.02, width, height}));
  scene->obstacles.push_back(
      panel("shelf_left", {0.686214596587107, 0.429596378159771, 0.277970677577637}, {depth, 0.02, height}));
  scene->obstacles.push_back(
      panel("shelf_right", {0.351765283065967, 0.22915662983659, 0.277970677577637}, {depth, 0.02, height}));
  for (const auto& [name, z] : {std::pair<std::string, double>{"shelf_bottom", 0.01},
                                {"shelf_middle", 0.277970677577637},
                                {"shelf_top", 0.545941355155275}}) {
    scene->obstacles.push_back(panel(name, {0.518989939826537, 0.329376503998181, z}, {depth, width, 0.02}));
  }
  robot::Vector6 start, goal;
  start << 1.07367532533337, -1.13982038660424, 1.82961550243109, -2.26059144262175, -1.57079632679489,
      1.07367532533337;
  goal << -0.391086349463711, -1.19936884167989, 1.8551187017125, -2.2265461868275, -1.5707963267949,
      -0.391086349463711;
  scene->queries[0].start = collision::QueryEndpoint{std::nullopt, std::nullopt, start};
  scene->queries[0].goal = collision::QueryEndpoint{std::nullopt, std::nullopt, goal};
  return planners::makePlanningProblem(scene);
}

inline const planners::ArcPlanner& arcOf(const ompl::base::PlannerPtr& planner) {
  return dynamic_cast<const planners::ArcPlanner&>(*planner);
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

// The smallest clearance a joint path meets, every motion sampled at 2 mrad: a second measurement, independent of
// the certified check the planner used, by the rule a clearance asks (collision::clearanceOf: the obstacle
// distance, a self pair's only below 1 mm; docs/collision.md#clearance).
inline double closestApproach(const planners::PlanningProblem& problem, const std::vector<robot::Vector6>& joints) {
  collision::CollisionData data(*problem.collisionModel);
  double closest = INFINITY;
  for (std::size_t i = 1; i < joints.size(); ++i) {
    const int samples = static_cast<int>(std::ceil((joints[i] - joints[i - 1]).cwiseAbs().maxCoeff() / 2e-3)) + 1;
    for (int k = 0; k <= samples; ++k) {
      const robot::Vector6 q = joints[i - 1] + (joints[i] - joints[i - 1]) * (double(k) / samples);
      closest = std::min(closest, collision::clearanceOf(collision::distance(*problem.collisionModel, data, q)));
    }
  }
  return closest;
}

// The same along the problem's solution path.
inline double closestApproach(const planners::PlanningProblem& problem) {
  return closestApproach(problem, collision::waypointsOf(problem.setup->getSolutionPath()));
}

}  // namespace arcplan::testing
