// The arc planner's bounds on its own search: the deadline after which the line-and-arc search gives
// up (falling back, or failing fast), whatever time the caller's termination condition leaves.
#include <gtest/gtest.h>
#include <ompl/base/PlannerStatus.h>

#include <string>

#include "arcplan/common/error.h"
#include "arcplan/planners/arc_planner.h"
#include "planners/planner_test_support.h"

namespace {

using arcplan::planners::ArcPlannerResult;
using namespace arcplan::testing;
namespace ob = ompl::base;

// The shelf needs dozens of routes (each a certified walk of about 0.1 ms or more): a search that
// cannot end within 0.1 ms.
constexpr const char* kTinyDeadline = "0.0001";

TEST(ArcPlannerDeadline, IsAParameterWithA50MillisecondDefault) {
  auto problem = shelfProblem();
  const auto planner =
      arcplan::planners::makePlanner("arc", problem.setup->getSpaceInformation(), problem.plannerContext());
  EXPECT_EQ(planner->params().getParam("deadline")->getValue(), "0.05");
  EXPECT_THROW(arcplan::planners::setPlannerParameters(*planner, {{"deadline", "-1"}}), arcplan::Error);
}

TEST(ArcPlannerDeadline, WithoutFallbackTheSearchFailsFastNamingTheDeadline) {
  auto problem = shelfProblem();
  // 10 s for the caller: only the deadline can end the search this early.
  const auto [planner, status] = solve(problem, "arc", {{"deadline", kTinyDeadline}, {"fallback", "0"}}, 10.0);
  const ArcPlannerResult& result = arcOf(planner).lastResult();
  EXPECT_EQ(status, ob::PlannerStatus::ABORT);
  EXPECT_EQ(result.kind, ArcPlannerResult::Kind::Failed);
  EXPECT_NE(result.reason.find("deadline of 0.1 ms reached"), std::string::npos) << result.reason;
}

TEST(ArcPlannerDeadline, WithFallbackTheRestOfTheTimeGoesToTheJointSpacePlanner) {
  auto problem = shelfProblem();
  const auto [planner, status] = solve(problem, "arc", {{"deadline", kTinyDeadline}}, 10.0);
  const ArcPlannerResult& result = arcOf(planner).lastResult();
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << result.reason;
  EXPECT_EQ(result.mode(), "fallback");
  EXPECT_NE(result.reason.find("deadline of 0.1 ms reached"), std::string::npos) << result.reason;
  EXPECT_GE(closestApproach(problem), 0.01 - 1e-6);
}

TEST(ArcPlannerDeadline, ZeroMeansNoDeadline) {
  auto problem = shelfProblem();
  const auto [planner, status] = solve(problem, "arc", {{"deadline", "0"}}, 10.0);
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  EXPECT_EQ(arcOf(planner).lastResult().mode(), "arc");
}

}  // namespace
