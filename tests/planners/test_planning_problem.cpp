// Scene query -> OMPL problem: endpoints from poses (seeded or default IK choice) or joints, and
// the errors for endpoints that cannot be used.
#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>

#include <algorithm>
#include <string>

#include "arcplan/common/error.h"
#include "arcplan/planners/planning_problem.h"
#include "planners/planner_test_support.h"

namespace {

using namespace arcplan::planners;
using arcplan::collision::QueryEndpoint;
using arcplan::robot::Vector6;
using arcplan::testing::loadTestScene;
using arcplan::testing::tcpPoses;

std::shared_ptr<arcplan::collision::Scene> editableScene(const std::string& name) {
  return std::make_shared<arcplan::collision::Scene>(*loadTestScene(name));
}

std::string problemError(const std::shared_ptr<arcplan::collision::Scene>& scene, const std::string& query = "") {
  try {
    makePlanningProblem(scene, query);
  } catch (const arcplan::Error& error) {
    return error.what();
  }
  return "(no error)";
}

const arcplan::robot::UrInverseKinematics& ik() {
  static const arcplan::robot::UrInverseKinematics solver(arcplan::robot::ur10e());
  return solver;
}

TEST(PlanningProblem, SeededPosesGiveTheSeedsPostureAtThePose) {
  const auto problem = makePlanningProblem(loadTestScene("thesis_obstacle"));
  EXPECT_EQ(problem.queryName, "A_to_B");
  const auto poses = tcpPoses({problem.start, problem.goal});
  EXPECT_LT((poses[0].translation() - arcplan::testing::thesisA()).norm(), 1e-9);
  EXPECT_LT((poses[1].translation() - arcplan::testing::thesisB()).norm(), 1e-9);
  EXPECT_LT(arcplan::robot::rotationDistance(poses[0].linear(), arcplan::testing::thesisToolDown()), 1e-9);
  // ur10e-facts §6 lists these elbow-up, wrist-down solutions (to 3 decimals): the seeds of the scene.
  const Vector6 factsStart = (Vector6() << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098).finished();
  EXPECT_LT((problem.start - factsStart).cwiseAbs().maxCoeff(), 1e-3);
  // The SimpleSetup starts and ends there.
  const auto& pdef = *problem.setup->getProblemDefinition();
  ASSERT_EQ(pdef.getStartStateCount(), 1u);
  const ompl::base::ScopedState<> start(problem.setup->getStateSpace(), pdef.getStartState(0));
  for (int j = 0; j < 6; ++j) EXPECT_EQ(start[j], problem.start[j]);
}

TEST(PlanningProblem, WithoutSeedTheCollisionFreeSolutionNearestTheUprightPostureIsUsed) {
  auto scene = editableScene("thesis_obstacle");
  scene->queries[0].start.seed.reset();
  const auto problem = makePlanningProblem(scene);
  // Independent choice: all solutions by distance to the upright posture, first collision-free.
  auto solutions = ik().solveAll(arcplan::robot::poseFromXyzRpy(*scene->queries[0].start.pose));
  std::sort(solutions.begin(), solutions.end(), [](const Vector6& x, const Vector6& y) {
    return (x - kDefaultIkSeed).norm() < (y - kDefaultIkSeed).norm();
  });
  arcplan::collision::CollisionData data(*problem.collisionModel);
  const auto first = std::find_if(solutions.begin(), solutions.end(), [&](const Vector6& q) {
    return arcplan::collision::isCollisionFree(*problem.collisionModel, data, q);
  });
  ASSERT_NE(first, solutions.end());
  EXPECT_EQ(problem.start, *first);
  EXPECT_EQ(kDefaultIkSeed, (Vector6() << 0.0, -M_PI_2, M_PI_2, -M_PI_2, -M_PI_2, 0.0).finished());
}

TEST(PlanningProblem, JointsAreUsedAsGiven) {
  auto scene = editableScene("thesis_free");
  const Vector6 q = (Vector6() << -1.0, -1.5, 2.3, -2.4, -1.571, -1.0).finished();
  scene->queries[0].start = QueryEndpoint{std::nullopt, std::nullopt, q};
  EXPECT_EQ(makePlanningProblem(scene).start, q);
}

TEST(PlanningProblem, JointsOutsideTheLimitsAreRejected) {
  auto scene = editableScene("thesis_free");
  scene->queries[0].goal =
      QueryEndpoint{std::nullopt, std::nullopt, (Vector6() << 0, -1.5, 3.5, -1.5, -1.5, 0).finished()};
  const std::string message = problemError(scene);
  EXPECT_NE(message.find("query 'A_to_B', goal"), std::string::npos) << message;
  EXPECT_NE(message.find("joint 2 (elbow_joint) = 3.5 rad is outside its limits"), std::string::npos) << message;
}

TEST(PlanningProblem, EndpointsInCollisionAreRejectedWithThePair) {
  auto scene = editableScene("thesis_obstacle");
  // An elbow-down solution of A: the arm lies on the table (ur10e-facts §6).
  const auto problem = makePlanningProblem(scene);
  arcplan::collision::CollisionData data(*problem.collisionModel);
  std::optional<Vector6> colliding;
  for (const auto& q : ik().solveAll(arcplan::robot::poseFromXyzRpy(*scene->queries[0].start.pose))) {
    if (!colliding && !arcplan::collision::isCollisionFree(*problem.collisionModel, data, q)) colliding = q;
  }
  ASSERT_TRUE(colliding);
  scene->queries[0].start = QueryEndpoint{std::nullopt, std::nullopt, *colliding};
  const std::string joints = problemError(scene);
  EXPECT_NE(joints.find("start: the joint configuration is in collision ("), std::string::npos) << joints;
  // The same posture as IK seed of the pose: the seed's solution collides.
  scene->queries[0].start =
      QueryEndpoint{loadTestScene("thesis_obstacle")->queries[0].start.pose, *colliding, std::nullopt};
  const std::string seeded = problemError(scene);
  EXPECT_NE(seeded.find("nearest to the seed"), std::string::npos) << seeded;
  EXPECT_NE(seeded.find("choose another seed"), std::string::npos) << seeded;
}

TEST(PlanningProblem, UnreachablePoseIsRejected) {
  auto scene = editableScene("thesis_free");
  scene->queries[0].goal =
      QueryEndpoint{std::array<double, 6>{3.0, 0.0, 0.3, 0.0, -M_PI, 0.0}, std::nullopt, std::nullopt};
  const std::string message = problemError(scene);
  EXPECT_NE(message.find("goal: the pose is out of reach"), std::string::npos) << message;
  EXPECT_NE(message.find("thesis_free.yaml"), std::string::npos) << message;
}

TEST(PlanningProblem, UnknownQueryIsRejected) {
  const std::string message = problemError(editableScene("thesis_free"), "B_to_A");
  EXPECT_NE(message.find("B_to_A"), std::string::npos) << message;
  EXPECT_NE(message.find("A_to_B"), std::string::npos) << message;
}

}  // namespace
