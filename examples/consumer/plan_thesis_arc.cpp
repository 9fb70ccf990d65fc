// A program of your own on an installed arcplan: plan the thesis query with the arc planner (case d,
// h = 0.5 r) through OMPL, then time-scale the path under the collaborative TCP speed limit.
#include <iostream>

#include <ompl/base/PlannerStatus.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <arcplan/collision/scene.h>
#include <arcplan/common/resources.h>
#include <arcplan/planners/planner_registry.h>
#include <arcplan/planners/planning_problem.h>
#include <arcplan/trajectory/metrics.h>
#include <arcplan/trajectory/time_scaling.h>

int main() {
  auto scene = std::make_shared<const arcplan::collision::Scene>(
      arcplan::collision::loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml"));
  auto problem = arcplan::planners::makePlanningProblem(scene);  // OMPL SimpleSetup with start and goal
  problem.setup->setPlanner(arcplan::planners::makePlanner("arc", problem.setup->getSpaceInformation(),
                                                           problem.plannerContext(), {{"sagitta", "0.1"}}));
  if (problem.setup->solve(1.0) != ompl::base::PlannerStatus::EXACT_SOLUTION) return 1;

  arcplan::trajectory::JointPath path;
  for (const auto* state : problem.setup->getSolutionPath().getStates()) {
    const auto* values = state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
    path.push_back(Eigen::Map<const arcplan::robot::Vector6>(values));
  }
  arcplan::trajectory::TimeScalingOptions limits;
  limits.maxTcpSpeed = 0.25;
  const auto trajectory = arcplan::trajectory::scaleToTcpSpeed(problem.collisionModel->robot(), path, limits);
  const auto metrics = arcplan::trajectory::computeMetrics(path, trajectory);
  std::cout << "tcp path length " << metrics.tcpPathLength << " m, execution time " << metrics.executionTime
            << " s, peak tcp speed " << metrics.peakTcpSpeed << " m/s\n";
  return metrics.peakTcpSpeed <= limits.maxTcpSpeed ? 0 : 1;
}
