#pragma once
// Problems the arc planner's fallback tests share (test_arc_planner_fallback*.cpp): a scene where only the
// joint-space fallback answers, posed at a benchmark suite's 1 cm clearance.
#include <ompl/geometric/PathGeometric.h>

#include <memory>
#include <vector>

#include "planners/planner_test_support.h"

namespace arcplan::testing {

// The problem of `scene` at a benchmark suite's 1 cm clearance (the arc planner's own): its fallback
// then plans on the problem's SpaceInformation, as plain RRTConnect does.
inline planners::PlanningProblem centimetreProblem(const std::shared_ptr<collision::Scene>& scene) {
  planners::PlanningProblemOptions options;
  options.clearance = 0.01;
  return planners::makePlanningProblem(scene, "", options);
}

inline std::vector<robot::Vector6> solutionJoints(const planners::PlanningProblem& problem) {
  return collision::waypointsOf(
      *problem.setup->getProblemDefinition()->getSolutionPath()->as<ompl::geometric::PathGeometric>());
}

// The generated suite's forearm-beam-009 (issue-23 families, seed 20240611): a 1.19 m beam at the elbow's
// height near the base axis. No line-and-arc route passes it, so the fallback answers.
inline std::shared_ptr<collision::Scene> elbowBeamScene() {
  auto scene = std::make_shared<collision::Scene>(*loadTestScene("thesis_free"));
  auto beam = box("beam", {0.195507084341427, -0.00222967505255894, 0.755856014615223},
                  {1.19452611899725, 0.0447951560837569, 0.0945077526952936});
  beam.pose.linear() = robot::rotationFromRpy(0.0, 0.0, 2.83093548283307);
  scene->obstacles.push_back(beam);
  robot::Vector6 start, goal;
  start << 1.2455732027649, -1.9210789748523, 2.46788163520193, -2.11759898714453, -1.57079632679489, 1.2455732027649;
  goal << 0.607349460295433, -1.01925237738874, 1.9625322279851, -2.51407617739126, -1.5707963267949, 0.607349460295433;
  scene->queries[0].start = collision::QueryEndpoint{std::nullopt, std::nullopt, start};
  scene->queries[0].goal = collision::QueryEndpoint{std::nullopt, std::nullopt, goal};
  return scene;
}

}  // namespace arcplan::testing
