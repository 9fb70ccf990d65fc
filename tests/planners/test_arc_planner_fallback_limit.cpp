// The arc planner's fallback under its time limit: the first plan's simplification runs to the end (as a
// benchmark run simplifies RRTConnect's path after its solve, untimed), everything after it stops at the
// limit with the best path so far. Work after the limit is counted in motion checks, not seconds: a
// termination condition fires once the problem's motion validator has checked a given number of motions.
#include <gtest/gtest.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/PlannerStatus.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "arcplan/collision/endpoint_clearance.h"
#include "arcplan/collision/ompl_validity.h"
#include "arcplan/planners/arc_planner.h"
#include "arcplan/planners/planner_registry.h"
#include "arcplan/planners/seeded_sampling.h"
#include "arcplan/trajectory/time_scaling.h"
#include "planners/arc_fallback_problems.h"
#include "planners/planner_test_support.h"

namespace {

using arcplan::planners::ArcPlannerResult;
using namespace arcplan::testing;
namespace ob = ompl::base;

constexpr std::uint32_t kSeed = 5;  // the arc planner's `seed`: its first plan draws what run seed 5 draws

// The problem's certified motion validator, counting the motions it checks.
class CountingMotionValidator : public arcplan::collision::JointMotionValidator {
public:
  using JointMotionValidator::JointMotionValidator;
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    ++checks;
    return JointMotionValidator::checkMotion(s1, s2);
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& lastValid) const override {
    ++checks;
    return JointMotionValidator::checkMotion(s1, s2, lastValid);
  }
  mutable long checks = 0;
};

// forearm-beam-009 at 1 cm with a counting motion validator in place of the problem's.
struct CountedProblem {
  arcplan::planners::PlanningProblem problem;
  std::shared_ptr<CountingMotionValidator> counting;
};
CountedProblem countedElbowBeamProblem() {
  CountedProblem counted{centimetreProblem(elbowBeamScene()), nullptr};
  const auto si = counted.problem.setup->getSpaceInformation();
  const auto* checker =
      dynamic_cast<const arcplan::collision::CollisionStateValidityChecker*>(si->getStateValidityChecker().get());
  const auto* validator = dynamic_cast<const arcplan::collision::JointMotionValidator*>(si->getMotionValidator().get());
  if (checker == nullptr || validator == nullptr) throw std::runtime_error("the problem has no collision validators");
  counted.counting = std::make_shared<CountingMotionValidator>(
      si.get(), counted.problem.collisionModel, validator->options(),
      std::make_shared<const arcplan::collision::EndpointClearance>(checker->requiredClearance()));
  si->setMotionValidator(counted.counting);
  return counted;
}

// Plain RRTConnect + OMPL's simplifier as a benchmark run with run seed kSeed computes them
// (SimpleSetup::solve, then SimpleSetup::simplifySolution(), i.e. PathSimplifier::simplifyMax; sampler
// and simplifier seeded by the campaign's seedSampling), with the motion checks each made.
struct RRTConnectAndSimplifyMax {
  long solveChecks = 0, simplifyChecks = 0;
  std::vector<arcplan::robot::Vector6> path;
  double executionTime = 0.0;  // s at 0.25 m/s
  // Motion checks from the start of the fallback's first plan to the end of its simplification: its
  // RRTConnect's, the simplifier's and one per motion of the result (certified_simplification.h).
  long firstPlanChecks() const { return solveChecks + simplifyChecks + static_cast<long>(path.size()) - 1; }
};
RRTConnectAndSimplifyMax rrtConnectAndSimplifyMax() {
  CountedProblem counted = countedElbowBeamProblem();
  ompl::geometric::SimpleSetup& setup = *counted.problem.setup;
  setup.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(setup.getSpaceInformation()));
  setup.setup();
  arcplan::planners::seedSampling(setup, kSeed);
  if (setup.solve(60.0) != ob::PlannerStatus::EXACT_SOLUTION) throw std::runtime_error("RRTConnect failed");
  RRTConnectAndSimplifyMax plan;
  plan.solveChecks = counted.counting->checks;
  setup.simplifySolution();
  plan.simplifyChecks = counted.counting->checks - plan.solveChecks;
  plan.path = solutionJoints(counted.problem);
  plan.executionTime = arcplan::trajectory::scaleToTcpSpeed(arcplan::robot::ur10e(), plan.path).duration();
  return plan;
}

struct BudgetedRun {
  ob::PlannerStatus status;
  long checks = 0, checksAfterTheLimit = 0;
  ArcPlannerResult result;
  std::vector<arcplan::robot::Vector6> joints;
};

// forearm-beam-009 at 1 cm solved by the arc planner (no search deadline, so only the budget decides)
// under a termination condition that fires once `budget` motions have been checked.
BudgetedRun solveWithinMotionChecks(long budget) {
  CountedProblem counted = countedElbowBeamProblem();
  auto& problem = counted.problem;
  const auto& counting = counted.counting;
  problem.setup->clear();
  auto planner = arcplan::planners::makePlanner("arc", problem.setup->getSpaceInformation(), problem.plannerContext(),
                                                {{"deadline", "0"}, {"seed", std::to_string(kSeed)}});
  problem.setup->setPlanner(planner);
  problem.setup->setup();
  BudgetedRun run;
  run.status = problem.setup->solve(ob::PlannerTerminationCondition([&] { return counting->checks >= budget; }));
  run.checks = counting->checks;
  run.checksAfterTheLimit = std::max(0L, counting->checks - budget);
  run.result = arcOf(planner).lastResult();
  if (run.status == ob::PlannerStatus::EXACT_SOLUTION) {
    run.joints = solutionJoints(problem);
    const auto path = problem.setup->getProblemDefinition()->getSolutionPath()->as<ompl::geometric::PathGeometric>();
    for (std::size_t i = 1; i < path->getStateCount(); ++i) {
      if (!counting->JointMotionValidator::checkMotion(path->getState(i - 1), path->getState(i)))
        throw std::runtime_error("the path returned has an invalid motion");
    }
  }
  return run;
}

// A limit that fires while the first plan is simplified does not cut that simplification: the path is then
// RRTConnect + simplifyMax of the same seed, computed above with OMPL directly, and nothing runs after it
// (no later plan, TCP shortcut or line makes a motion check). Before, the condition stopped the simplifier
// and the fallback returned a less simplified path.
TEST(ArcPlannerFallbackLimit, SimplifiesItsFirstPlanToTheEndWhenTheLimitFiresMeanwhile) {
  const RRTConnectAndSimplifyMax expected = rrtConnectAndSimplifyMax();
  ASSERT_GE(expected.simplifyChecks, 2);
  const BudgetedRun run = solveWithinMotionChecks(expected.solveChecks + expected.simplifyChecks / 2);
  ASSERT_EQ(run.status, ob::PlannerStatus::EXACT_SOLUTION) << run.result.reason;
  ASSERT_EQ(run.result.mode(), "fallback");
  ASSERT_EQ(run.joints.size(), expected.path.size()) << run.result.reason;
  for (std::size_t i = 0; i < run.joints.size(); ++i)
    EXPECT_LT((run.joints[i] - expected.path[i]).norm(), 1e-12) << "waypoint " << i;
  EXPECT_NEAR(run.result.fallbackTimes.firstPlan, expected.executionTime, 1e-9);
  EXPECT_NEAR(run.result.fallbackTimes.kept, expected.executionTime, 1e-9);
  EXPECT_EQ(run.checks, expected.firstPlanChecks());
  // Reported apart from the solve time, as a benchmark reports RRTConnect's simplification.
  EXPECT_GT(run.result.simplificationTime, 0.0);
}

// The first plan's simplification is reported as a benchmark reports RRTConnect's: apart from the solve
// time, in the planner data's "simplification time REAL" (which OMPL's Benchmark copies into the run);
// together they are the planner's call, which SimpleSetup times from outside.
TEST(ArcPlannerFallbackLimit, ReportsItsFirstPlansSimplificationApartFromItsSolveTime) {
  auto problem = centimetreProblem(elbowBeamScene());
  const auto [planner, status] = solve(problem, "arc", {{"seed", std::to_string(kSeed)}}, 30.0);
  const ArcPlannerResult& result = arcOf(planner).lastResult();
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << result.reason;
  ASSERT_EQ(result.mode(), "fallback");
  EXPECT_GT(result.simplificationTime, 0.0);
  EXPECT_GT(result.solveTime, 0.0);
  EXPECT_LE(result.solveTime + result.simplificationTime, problem.setup->getLastPlanComputationTime());
  ob::PlannerData data(problem.setup->getSpaceInformation());
  planner->getPlannerData(data);
  EXPECT_NEAR(std::stod(data.properties.at("simplification time REAL")), result.simplificationTime, 1e-9);
  EXPECT_NEAR(std::stod(data.properties.at("solve time REAL")), result.solveTime, 1e-9);
}

// Everything after the first plan stops at the limit: a limit that fires while the fallback plans again,
// shortcuts or converts its path makes no motion check after it (a later plan's simplifier is refused
// every motion from then on, a TCP shortcut polls the condition before its check), and the best path so
// far is returned. Before, the simplifier step under way ran on: up to 120 checks after the limit here
// (smoothBSpline's 3 subdivisions), with OMPL's default (atLeastOnce) a whole pass, up to 490.
TEST(ArcPlannerFallbackLimit, StopsAtItsTimeLimitWithTheBestPathSoFar) {
  const RRTConnectAndSimplifyMax first = rrtConnectAndSimplifyMax();
  const BudgetedRun unlimited = solveWithinMotionChecks(std::numeric_limits<long>::max());
  ASSERT_EQ(unlimited.status, ob::PlannerStatus::EXACT_SOLUTION) << unlimited.result.reason;
  ASSERT_EQ(unlimited.result.mode(), "fallback");
  // Budgets from 6 % to 44 % of the unlimited run's checks: its first plan (RRTConnect, then the
  // simplifier) ends at about a quarter of them.
  ASSERT_LT(first.firstPlanChecks(), unlimited.checks * 40 / 100);
  bool solvedBefore = false;
  int firedWhileSimplifying = 0, improvedBeforeTheLimit = 0;
  for (int percent = 6; percent <= 44; percent += 2) {
    const long budget = unlimited.checks * percent / 100;
    const BudgetedRun run = solveWithinMotionChecks(budget);
    // Past the limit only the rest of the first plan's simplification, if the limit fired before it ended.
    EXPECT_LE(run.checks, std::max(budget, first.firstPlanChecks()))
        << "budget " << budget << ": " << run.result.reason;
    const bool solved = run.status == ob::PlannerStatus::EXACT_SOLUTION;
    // Once a path was found within a budget, every larger budget returns one.
    EXPECT_TRUE(solved || !solvedBefore) << "budget " << budget << ": " << run.result.reason;
    solvedBefore = solvedBefore || solved;
    if (!solved) continue;
    EXPECT_EQ(run.result.mode(), "fallback");
    EXPECT_NEAR(run.result.fallbackTimes.firstPlan, first.executionTime, 1e-9) << "budget " << budget;
    EXPECT_LE(run.result.fallbackTimes.kept, first.executionTime + 1e-9) << "budget " << budget;
    EXPECT_LT((run.joints.front() - unlimited.joints.front()).norm(), 1e-12);
    EXPECT_LT((run.joints.back() - unlimited.joints.back()).norm(), 1e-12);
    firedWhileSimplifying += budget > first.solveChecks && budget < first.firstPlanChecks() ? 1 : 0;
    improvedBeforeTheLimit += budget > first.firstPlanChecks() && run.result.fallbackTimes.kept < first.executionTime;
  }
  EXPECT_GT(firedWhileSimplifying, 0) << "no budget fired while the first plan was simplified";
  EXPECT_GT(improvedBeforeTheLimit, 0) << "no budget fired after work past the first plan had paid";
}

}  // namespace
