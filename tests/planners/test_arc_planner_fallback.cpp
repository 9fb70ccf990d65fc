// The arc planner's joint-space fallback: RRTConnect (seeded by the planner as a benchmark run seeds
// RRTConnect) + OMPL's simplifier, then the fastest at the speed limit of that joint path, its segments
// as TCP lines where they validate, and mixes of the two; valid, repeatable, and never slower to execute
// than RRTConnect + simplifier of the same seed (its time limit: test_arc_planner_fallback_limit.cpp).
#include <gtest/gtest.h>
#include <ompl/base/PlannerStatus.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/endpoint_clearance.h"
#include "arcplan/common/error.h"
#include "arcplan/planners/arc_planner.h"
#include "arcplan/planners/seeded_sampling.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/ur_inverse_kinematics.h"
#include "arcplan/trajectory/time_scaling.h"
#include "planners/arc_fallback_problems.h"
#include "planners/planner_test_support.h"

namespace {

using arcplan::planners::ArcPlannerResult;
using namespace arcplan::testing;
namespace ob = ompl::base;

// The goal pose of thesis_free on another IK branch (the first in-limit solution of another branch
// that keeps 2 cm from the table): no TCP path keeps one branch between start and goal, so the
// answer is the joint-space fallback.
arcplan::planners::PlanningProblem goalOnAnotherBranchProblem() {
  auto scene = std::make_shared<arcplan::collision::Scene>(*loadTestScene("thesis_free"));
  auto problem = arcplan::planners::makePlanningProblem(scene);
  const arcplan::robot::UrInverseKinematics ik(arcplan::robot::ur10e());
  arcplan::collision::CollisionData data(*problem.collisionModel);
  std::optional<arcplan::robot::Vector6> other;
  for (const auto& candidate : ik.solveAll(tcpPoses({problem.goal})[0])) {
    if (!other && ik.branchOf(candidate) != ik.branchOf(problem.goal) &&
        arcplan::collision::distance(*problem.collisionModel, data, candidate).minimum() > 0.02) {
      other = candidate;
    }
  }
  if (!other) throw std::runtime_error("thesis_free's goal pose has no clear solution on another IK branch");
  scene->queries[0].goal = arcplan::collision::QueryEndpoint{std::nullopt, std::nullopt, *other};
  return arcplan::planners::makePlanningProblem(scene);
}

TEST(ArcPlannerFallback, JoinsTwoIkBranchesWithAValidPath) {
  auto problem = goalOnAnotherBranchProblem();
  const auto [planner, status] = solve(problem, "arc");
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  const ArcPlannerResult& result = arcOf(planner).lastResult();
  EXPECT_EQ(result.mode(), "fallback");
  EXPECT_EQ(result.kind, ArcPlannerResult::Kind::Fallback);
  EXPECT_GE(result.cartesianFraction, 0.0);
  EXPECT_LE(result.cartesianFraction, 1.0);
  const auto joints = solutionJoints(problem);
  ASSERT_GE(joints.size(), 2u);
  EXPECT_LT((joints.front() - problem.start).norm(), 1e-12);
  EXPECT_LT((joints.back() - problem.goal).norm(), 1e-12);
  // Valid for the SpaceInformation (every state and every motion, certified), and it keeps the
  // planner's 1 cm clearance, measured independently at 0.01 rad along every motion.
  const auto si = problem.setup->getSpaceInformation();
  const auto path = problem.setup->getProblemDefinition()->getSolutionPath()->as<ompl::geometric::PathGeometric>();
  EXPECT_TRUE(path->check());
  for (std::size_t i = 1; i < path->getStateCount(); ++i) {
    EXPECT_TRUE(si->checkMotion(path->getState(i - 1), path->getState(i))) << "motion " << i;
  }
  EXPECT_GE(closestApproach(problem), 0.01 - 1e-6);
}

// A goal 5 mm from a block (a grasp): near it, in its approach zone, paths may come as close as half
// that; everywhere else they keep the 1 cm the benchmark judges them by (collision/endpoint_clearance.h).
// The fallback plans with that rule, not with the goal's 5 mm along the whole path.
TEST(ArcPlannerFallback, KeepsTheClearanceOutsideTheGoalsApproachZone) {
  auto problem = goalOnAnotherBranchProblem();
  auto scene = std::make_shared<arcplan::collision::Scene>(*problem.scene);
  const arcplan::robot::Vector6 goal = problem.goal;
  const Eigen::Isometry3d tip = arcplan::robot::tipPose(arcplan::robot::ur10e(), goal);
  // A 4 cm block on the tool's axis beyond the TCP, moved until the goal is 5 mm from it.
  double offset = 0.04, clearance = 0.0;
  for (int attempt = 0; attempt < 8 && std::abs(clearance - 0.005) > 2e-4; ++attempt) {
    scene->obstacles.push_back(box("block", tip * Eigen::Vector3d(0.0, 0.0, offset), {0.04, 0.04, 0.04}));
    const auto model = arcplan::planners::makePlanningProblem(scene).collisionModel;
    arcplan::collision::CollisionData data(*model);
    clearance = arcplan::collision::distance(*model, data, goal).obstacleDistance;
    offset -= clearance - 0.005;
    if (std::abs(clearance - 0.005) > 2e-4) scene->obstacles.pop_back();
  }
  ASSERT_NEAR(clearance, 0.005, 2e-4);
  scene->queries[0].goal = arcplan::collision::QueryEndpoint{std::nullopt, std::nullopt, goal};
  arcplan::planners::PlanningProblemOptions options;
  options.clearance = 0.01;
  auto blocked = arcplan::planners::makePlanningProblem(scene, "", options);
  const auto [planner, status] = solve(blocked, "arc", {}, 20.0);
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  ASSERT_EQ(arcOf(planner).lastResult().mode(), "fallback");
  // Judged state by state: every state at 2 mrad steps along each motion keeps what the rule asks of that
  // state (1 cm, the zone's 2.5 mm only inside the goal's zone; from obstacles, the arm's own links 1 mm:
  // clearanceOf), as motions certified piece by piece do.
  const arcplan::collision::EndpointClearance rule(
      *blocked.collisionModel, 0.01, 0.01,
      {arcplan::robot::JointVector(blocked.start), arcplan::robot::JointVector(blocked.goal)});
  ASSERT_EQ(rule.zones().size(), 1u);
  const auto joints = solutionJoints(blocked);
  arcplan::collision::CollisionData data(*blocked.collisionModel);
  int outsideTheZone = 0;
  for (std::size_t i = 1; i < joints.size(); ++i) {
    const int samples = static_cast<int>(std::ceil((joints[i] - joints[i - 1]).cwiseAbs().maxCoeff() / 2e-3)) + 1;
    for (int k = 0; k <= samples; ++k) {
      const arcplan::robot::Vector6 q = joints[i - 1] + (joints[i] - joints[i - 1]) * (double(k) / samples);
      const double required = rule.stateClearanceAt(q);
      outsideTheZone += required == 0.01 ? 1 : 0;
      EXPECT_GE(arcplan::collision::clearanceOf(arcplan::collision::distance(*blocked.collisionModel, data, q)),
                required - 1e-6)
          << "motion " << i << " of " << joints.size() - 1 << ", step " << k;
    }
  }
  EXPECT_GT(outsideTheZone, 0) << "every state was in the goal's zone: nothing was judged at 1 cm";
}

TEST(ArcPlannerFallback, GivesTheSamePathWhateverRanBefore) {
  auto problem = goalOnAnotherBranchProblem();
  const auto [first, firstStatus] = solve(problem, "arc");
  ASSERT_EQ(firstStatus, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(first).lastResult().reason;
  ASSERT_EQ(arcOf(first).lastResult().mode(), "fallback");
  const auto firstJoints = solutionJoints(problem);
  // Another planner draws from OMPL's process-wide generator in between.
  const auto [other, otherStatus] = solve(problem, "RRTConnect");
  ASSERT_EQ(otherStatus, ob::PlannerStatus::EXACT_SOLUTION);
  const auto [second, secondStatus] = solve(problem, "arc");
  ASSERT_EQ(secondStatus, ob::PlannerStatus::EXACT_SOLUTION);
  const auto secondJoints = solutionJoints(problem);
  ASSERT_EQ(secondJoints.size(), firstJoints.size());
  for (std::size_t i = 0; i < firstJoints.size(); ++i) EXPECT_EQ(secondJoints[i], firstJoints[i]) << "waypoint " << i;
  // The seed is what fixes it: another seed draws other samples.
  const auto [reseeded, reseededStatus] = solve(problem, "arc", {{"seed", "7"}});
  ASSERT_EQ(reseededStatus, ob::PlannerStatus::EXACT_SOLUTION);
  EXPECT_NE(solutionJoints(problem), firstJoints);
}

// The generated suite's line-box-025 (seed 20240611) on thesis_free's table: a box beside the TCP line,
// start and goal as joints. Before the fallback compared execution times, its path (RRTConnect +
// simplifier, every segment turned into a TCP line) took 14.52 s to execute at 0.25 m/s, RRTConnect +
// simplifier alone 5.819 s (generated suite, 1 run each at 1 cm clearance). A 0.1 ms deadline cuts the
// line search short, so the fallback answers.
arcplan::planners::PlanningProblem boxBesideTheLineProblem() {
  auto scene = std::make_shared<arcplan::collision::Scene>(*loadTestScene("thesis_free"));
  auto obstacle = box("obstacle", {0.428594309141047, -0.300333303369862, 0.353547448035524},
                      {0.116858325315643, 0.0829721865416261, 0.139415097946088});
  obstacle.pose.linear() = arcplan::robot::rotationFromRpy(0.0, 0.0, -2.28339469896718);
  scene->obstacles.push_back(obstacle);
  arcplan::robot::Vector6 start, goal;
  start << -0.232305886836035, -1.58424985642398, 2.31451015198332, -2.30105662235423, -1.5707963267949,
      -0.232305886836035;
  goal << -1.18883255515116, -1.32765894814633, 2.10198643822263, -2.34512381687119, -1.5707963267949,
      -1.18883255515116;
  scene->queries[0].start = arcplan::collision::QueryEndpoint{std::nullopt, std::nullopt, start};
  scene->queries[0].goal = arcplan::collision::QueryEndpoint{std::nullopt, std::nullopt, goal};
  return arcplan::planners::makePlanningProblem(scene);
}

TEST(ArcPlannerFallback, IsNeverSlowerThanItsJointPathNorThanRRTConnectWasHere) {
  auto problem = boxBesideTheLineProblem();
  const auto [planner, status] = solve(problem, "arc", {{"deadline", "0.0001"}}, 20.0);
  const ArcPlannerResult& result = arcOf(planner).lastResult();
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << result.reason;
  ASSERT_EQ(result.mode(), "fallback");
  const ArcPlannerResult::FallbackTimes& times = result.fallbackTimes;
  // The fastest of the joint path, its lines and their mixes is kept.
  EXPECT_LE(times.kept, times.jointPath);
  EXPECT_LE(times.kept, times.linePath);
  EXPECT_LE(times.kept, 5.819) << "slower than RRTConnect + simplifier in the generated suite";
  EXPECT_NE(result.reason.find("the fallback kept"), std::string::npos) << result.reason;
  // The time reported is the time of the path returned, measured as `arcplan plan` and `bench` do.
  const auto joints = solutionJoints(problem);
  const double measured = arcplan::trajectory::scaleToTcpSpeed(arcplan::robot::ur10e(), joints).duration();
  EXPECT_NEAR(measured, times.kept, 1e-9);
  EXPECT_LT((joints.front() - problem.start).norm(), 1e-12);
  EXPECT_LT((joints.back() - problem.goal).norm(), 1e-12);
  const auto si = problem.setup->getSpaceInformation();
  const auto path = problem.setup->getProblemDefinition()->getSolutionPath()->as<ompl::geometric::PathGeometric>();
  for (std::size_t i = 1; i < path->getStateCount(); ++i) {
    EXPECT_TRUE(si->checkMotion(path->getState(i - 1), path->getState(i))) << "motion " << i;
  }
  EXPECT_GE(closestApproach(problem), 0.01 - 1e-6);
}

// Execution time at 0.25 m/s of plain RRTConnect + simplifier as a benchmark run seeded with `seed`
// computes it (SimpleSetup::solve, then SimpleSetup::simplifySolution(), at the suite's 1 cm clearance,
// its sampler and simplifier seeded by the campaign's planners::seedSampling), RRTConnect's `range` set
// where `range` > 0 as a suite's planner params set it.
double rrtConnectAndSimplifier(const std::shared_ptr<arcplan::collision::Scene>& scene, std::uint32_t seed,
                               double range = 0.0) {
  auto problem = centimetreProblem(scene);
  const auto si = problem.setup->getSpaceInformation();
  auto rrtConnect = std::make_shared<ompl::geometric::RRTConnect>(si);
  if (range > 0.0) rrtConnect->setRange(range);
  problem.setup->setPlanner(rrtConnect);
  problem.setup->setup();
  arcplan::planners::seedSampling(*problem.setup, seed);
  if (problem.setup->solve(20.0) != ob::PlannerStatus::EXACT_SOLUTION) throw std::runtime_error("RRTConnect failed");
  problem.setup->simplifySolution();
  return arcplan::trajectory::scaleToTcpSpeed(arcplan::robot::ur10e(), solutionJoints(problem)).duration();
}

TEST(ArcPlannerFallback, ItsFirstPlanIsRRTConnectAndSimplifierOfTheSameSeed) {
  const auto scene = elbowBeamScene();
  auto problem = centimetreProblem(scene);
  constexpr std::uint32_t kSeed = 5;
  const auto [planner, status] = solve(problem, "arc", {{"seed", std::to_string(kSeed)}}, 30.0);
  const ArcPlannerResult& result = arcOf(planner).lastResult();
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << result.reason;
  ASSERT_EQ(result.mode(), "fallback") << result.reason;
  // Its joint-space plans draw from seeds 5..8, the first from what a benchmark run with run seed 5
  // gives plain RRTConnect: each is recomputed here the way the campaign computes it, on the same
  // problem; the fastest is the one the fallback compares ...
  const double sameSeed = rrtConnectAndSimplifier(scene, kSeed);
  double fastest = sameSeed;
  for (std::uint32_t seed = kSeed + 1; seed <= kSeed + 3; ++seed)
    fastest = std::min(fastest, rrtConnectAndSimplifier(scene, seed));
  EXPECT_NEAR(result.fallbackTimes.jointPath, fastest, 1e-9);
  // ... so what it keeps executes no slower than RRTConnect + simplifier of the same seed.
  EXPECT_LE(result.fallbackTimes.kept, sameSeed);
  EXPECT_NEAR(arcplan::trajectory::scaleToTcpSpeed(arcplan::robot::ur10e(), solutionJoints(problem)).duration(),
              result.fallbackTimes.kept, 1e-9);
  EXPECT_GE(closestApproach(problem), 0.01 - 1e-6);
}

// With fallback_plans 1 the fallback draws the same-seed plan alone: its joint path is exactly what RRTConnect +
// simplifier of that seed executes (not the fastest of four draws), and what it keeps is no slower.
TEST(ArcPlannerFallback, OnePlanIsRRTConnectAndSimplifierOfTheSameSeed) {
  const auto scene = elbowBeamScene();
  auto problem = centimetreProblem(scene);
  constexpr std::uint32_t kSeed = 5;
  const auto [planner, status] =
      solve(problem, "arc", {{"seed", std::to_string(kSeed)}, {"fallback_plans", "1"}}, 30.0);
  const ArcPlannerResult& result = arcOf(planner).lastResult();
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << result.reason;
  ASSERT_EQ(result.mode(), "fallback") << result.reason;
  const double sameSeed = rrtConnectAndSimplifier(scene, kSeed);
  // One of the later draws executes faster (else this test could not tell one plan from four).
  double later = rrtConnectAndSimplifier(scene, kSeed + 1);
  for (std::uint32_t seed = kSeed + 2; seed <= kSeed + 3; ++seed)
    later = std::min(later, rrtConnectAndSimplifier(scene, seed));
  ASSERT_LT(later, sameSeed - 1e-6);
  EXPECT_NEAR(result.fallbackTimes.jointPath, sameSeed, 1e-9);
  EXPECT_LE(result.fallbackTimes.kept, sameSeed);
  EXPECT_NE(result.reason.find("the fastest of 1 RRTConnect"), std::string::npos) << result.reason;
}

// fallback_plans and fallback_threads: whole numbers from 1 to 8, anything else a clear error naming the parameter.
TEST(ArcPlannerFallback, APlanOrThreadCountThatIsNotAWholeNumberFrom1To8IsAnError) {
  const auto scene = elbowBeamScene();
  auto problem = centimetreProblem(scene);
  for (const char* parameter : {"fallback_plans", "fallback_threads"}) {
    for (const char* bad : {"0", "9", "2.5", "nan"}) {
      try {
        solve(problem, "arc", {{parameter, bad}}, 1.0);
        ADD_FAILURE() << parameter << "=" << bad << " was accepted";
      } catch (const arcplan::Error& error) {
        EXPECT_NE(std::string(error.what()).find(parameter), std::string::npos) << error.what();
      }
    }
  }
}

// Plans drawn on several threads at once are the same plans, taken in the same order: the path, its execution times
// and the reason are those of the fallback drawing them one after the other (the expected values: that serial run).
TEST(ArcPlannerFallback, PlansDrawnOnSeveralThreadsGiveTheSamePath) {
  const auto scene = elbowBeamScene();
  auto serialProblem = centimetreProblem(scene), threadedProblem = centimetreProblem(scene);
  const auto [serial, serialStatus] = solve(serialProblem, "arc", {{"seed", "5"}, {"fallback_threads", "1"}}, 30.0);
  const auto [threaded, threadedStatus] =
      solve(threadedProblem, "arc", {{"seed", "5"}, {"fallback_threads", "3"}}, 30.0);
  const ArcPlannerResult& one = arcOf(serial).lastResult();
  const ArcPlannerResult& three = arcOf(threaded).lastResult();
  ASSERT_EQ(serialStatus, ob::PlannerStatus::EXACT_SOLUTION) << one.reason;
  ASSERT_EQ(threadedStatus, ob::PlannerStatus::EXACT_SOLUTION) << three.reason;
  ASSERT_EQ(one.mode(), "fallback") << one.reason;
  EXPECT_EQ(three.mode(), "fallback");
  const auto serialJoints = solutionJoints(serialProblem), threadedJoints = solutionJoints(threadedProblem);
  ASSERT_EQ(threadedJoints.size(), serialJoints.size());
  for (std::size_t i = 0; i < serialJoints.size(); ++i)
    EXPECT_EQ(threadedJoints[i], serialJoints[i]) << "waypoint " << i;
  EXPECT_EQ(three.fallbackTimes.firstPlan, one.fallbackTimes.firstPlan);
  EXPECT_EQ(three.fallbackTimes.jointPath, one.fallbackTimes.jointPath);
  EXPECT_EQ(three.fallbackTimes.kept, one.fallbackTimes.kept);
  EXPECT_EQ(three.reason, one.reason);
}

// A suite that sets RRTConnect's range gives the fallback the same (fallback_range): its plans are then
// those of RRTConnect with that range, not with RRTConnect's default (0.2 of the joint space's extent,
// 3.2 rad on the UR10e's thesis limits).
TEST(ArcPlannerFallback, ItsPlansTakeTheRangeGivenToRRTConnect) {
  const auto scene = elbowBeamScene();
  auto problem = centimetreProblem(scene);
  constexpr std::uint32_t kSeed = 5;
  constexpr double kRange = 0.8;
  const auto [planner, status] =
      solve(problem, "arc", {{"seed", std::to_string(kSeed)}, {"fallback_range", std::to_string(kRange)}}, 30.0);
  const ArcPlannerResult& result = arcOf(planner).lastResult();
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << result.reason;
  ASSERT_EQ(result.mode(), "fallback") << result.reason;
  double withRange = rrtConnectAndSimplifier(scene, kSeed, kRange);
  double withDefault = rrtConnectAndSimplifier(scene, kSeed);
  for (std::uint32_t seed = kSeed + 1; seed <= kSeed + 3; ++seed) {
    withRange = std::min(withRange, rrtConnectAndSimplifier(scene, seed, kRange));
    withDefault = std::min(withDefault, rrtConnectAndSimplifier(scene, seed));
  }
  // The range changes the plans (else this test could not tell), and the fallback's are the ranged ones.
  ASSERT_GT(std::abs(withRange - withDefault), 1e-6);
  EXPECT_NEAR(result.fallbackTimes.jointPath, withRange, 1e-9);
}

}  // namespace
