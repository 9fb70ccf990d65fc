// The planner registry: names, allocation, parameters by name and their errors.
#include <gtest/gtest.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <chrono>
#include <string>

#include "arcplan/common/error.h"
#include "arcplan/planners/planner_registry.h"
#include "planners/planner_test_support.h"
#include "support/error_message.h"

namespace {

using arcplan::testing::errorMessageOf;

using namespace arcplan::planners;
using arcplan::testing::thesisProblem;

TEST(PlannerRegistry, HasTheArcPlannerFirstAndTheRequiredOmplPlanners) {
  const auto& names = plannerNames();
  ASSERT_FALSE(names.empty());
  EXPECT_EQ(names.front(), "arc");
  for (const char* required : {"RRT", "RRTConnect", "RRTstar", "PRM", "PRMstar", "LazyPRM", "BKPIECE1", "KPIECE1",
                               "EST", "SBL", "BiTRRT", "InformedRRTstar", "BITstar"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), required), names.end()) << required;
  }
}

TEST(PlannerRegistry, EveryNameAllocatesThePlannerOfThatName) {
  auto problem = thesisProblem("thesis_free");
  for (const std::string& name : plannerNames()) {
    const auto planner = makePlanner(name, problem.setup->getSpaceInformation(), problem.plannerContext());
    ASSERT_NE(planner, nullptr) << name;
    // OMPL names RRTsharp "RRT#"; the registry keeps a name that is easy to type.
    EXPECT_EQ(planner->getName(), name == "RRTsharp" ? "RRT#" : name);
    EXPECT_EQ(planner->getSpaceInformation(), problem.setup->getSpaceInformation());
  }
}

TEST(PlannerRegistry, NamesMatchIgnoringCaseAndUnknownNamesListTheKnownOnes) {
  EXPECT_EQ(canonicalPlannerName("rrtconnect"), "RRTConnect");
  EXPECT_EQ(canonicalPlannerName("ARC"), "arc");
  EXPECT_TRUE(isArcPlanner("Arc"));
  EXPECT_FALSE(isArcPlanner("PRM"));
  const std::string message = errorMessageOf([] { canonicalPlannerName("RRTConect"); });
  EXPECT_NE(message.find("unknown planner 'RRTConect'"), std::string::npos) << message;
  EXPECT_NE(message.find("RRTConnect"), std::string::npos) << message;
  EXPECT_NE(message.find("BITstar"), std::string::npos) << message;
}

TEST(PlannerRegistry, ParametersAreSetByName) {
  auto problem = thesisProblem("thesis_free");
  const auto rrt =
      makePlanner("RRTConnect", problem.setup->getSpaceInformation(), problem.plannerContext(), {{"range", "0.2"}});
  EXPECT_DOUBLE_EQ(dynamic_cast<ompl::geometric::RRTConnect&>(*rrt).getRange(), 0.2);
  const auto prm = makePlanner("PRM", problem.setup->getSpaceInformation(), problem.plannerContext(),
                               {{"max_nearest_neighbors", "9"}});
  EXPECT_EQ(dynamic_cast<ompl::geometric::PRM&>(*prm).getMaxNearestNeighbors(), 9u);
}

TEST(PlannerRegistry, UnknownParameterListsTheValidOnes) {
  auto problem = thesisProblem("thesis_free");
  const std::string message = errorMessageOf([&] {
    makePlanner("RRTConnect", problem.setup->getSpaceInformation(), problem.plannerContext(), {{"rang", "0.2"}});
  });
  EXPECT_NE(message.find("RRTConnect has no parameter 'rang'"), std::string::npos) << message;
  EXPECT_NE(message.find("range="), std::string::npos) << message;
  const std::string arc = errorMessageOf([&] {
    makePlanner("arc", problem.setup->getSpaceInformation(), problem.plannerContext(), {{"height", "0.1"}});
  });
  EXPECT_NE(arc.find("sagitta="), std::string::npos) << arc;
  EXPECT_NE(arc.find("plane_angle="), std::string::npos) << arc;
}

TEST(PlannerRegistry, ValueThePlannerCannotTakeIsRejected) {
  auto problem = thesisProblem("thesis_free");
  const std::string message = errorMessageOf([&] {
    makePlanner("RRTConnect", problem.setup->getSpaceInformation(), problem.plannerContext(), {{"range", "far"}});
  });
  EXPECT_NE(message.find("parameter 'range' does not accept 'far'"), std::string::npos) << message;
  const std::string arc = errorMessageOf([&] {
    makePlanner("arc", problem.setup->getSpaceInformation(), problem.plannerContext(), {{"resolution", "-0.01"}});
  });
  EXPECT_NE(arc.find("parameter 'resolution' does not accept '-0.01'"), std::string::npos) << arc;
  EXPECT_NE(arc.find("[0.001, 0.1]"), std::string::npos) << arc;
}

TEST(PlannerRegistry, ValuesOutsideTheDeclaredRangeAreRejected) {
  // OMPL declares RRTConnect's range as "0.:1.:10000." and PRM's neighbours as "8:1000"; its setters
  // themselves would take -1 and 3.
  auto problem = thesisProblem("thesis_free");
  const std::string range = errorMessageOf([&] {
    makePlanner("RRTConnect", problem.setup->getSpaceInformation(), problem.plannerContext(), {{"range", "-1"}});
  });
  EXPECT_NE(range.find("parameter 'range' does not accept '-1': expected a number in [0, 10000]"), std::string::npos)
      << range;
  const std::string neighbours = errorMessageOf([&] {
    makePlanner("PRM", problem.setup->getSpaceInformation(), problem.plannerContext(),
                {{"max_nearest_neighbors", "3"}});
  });
  EXPECT_NE(neighbours.find("[8, 1000]"), std::string::npos) << neighbours;
  EXPECT_NO_THROW(
      makePlanner("RRTConnect", problem.setup->getSpaceInformation(), problem.plannerContext(), {{"range", "10000"}}));
}

TEST(PlannerRegistry, ParameterAssignmentsNeedNameAndValue) {
  EXPECT_EQ(parseParameterAssignment("range=0.2"), (std::pair<std::string, std::string>{"range", "0.2"}));
  EXPECT_EQ(parseParameterAssignment("goal_bias=0.05=x").second, "0.05=x");
  for (const char* bad : {"range", "=0.2", "range=", ""}) {
    EXPECT_NE(errorMessageOf([&] { parseParameterAssignment(bad); }).find("NAME=VALUE"), std::string::npos) << bad;
  }
}

TEST(PlannerRegistry, ArcPlannerNeedsTheCollisionModel) {
  auto problem = thesisProblem("thesis_free");
  EXPECT_NE(errorMessageOf([&] { plannerAllocator("arc", PlannerContext{}); }).find("collision model"),
            std::string::npos);
}

TEST(PlannerRegistry, EveryPlannerTimesItsOwnSolveAndReportsItInItsPlannerData) {
  auto problem = thesisProblem("thesis_free");
  for (const std::string& name : plannerNames()) {
    const auto planner = makePlanner(name, problem.setup->getSpaceInformation(), problem.plannerContext());
    planner->setProblemDefinition(problem.setup->getProblemDefinition());
    problem.setup->getProblemDefinition()->clearSolutionPaths();
    // As OMPL's Benchmark calls it: the termination condition evaluated on a thread of its own every 0.1 s, whose
    // join the clock around this call counts and the planner's own does not.
    const auto start = std::chrono::steady_clock::now();
    planner->solve(ompl::base::timedPlannerTerminationCondition(0.02), 0.1);
    const double around = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double own = lastSolveTime(*planner);
    EXPECT_GT(own, 0.0) << name;
    EXPECT_LE(own, around) << name;
    ompl::base::PlannerData data(problem.setup->getSpaceInformation());
    planner->getPlannerData(data);
    ASSERT_EQ(data.properties.count("solve time REAL"), 1u) << name;
    EXPECT_NEAR(std::stod(data.properties.at("solve time REAL")), own, 1e-9 * own) << name;
  }
}

TEST(PlannerRegistry, SolveTimeIsOnlyForPlannersTheRegistryMade) {
  auto problem = thesisProblem("thesis_free");
  const ompl::geometric::RRTConnect unregistered(problem.setup->getSpaceInformation());
  const std::string message = errorMessageOf([&] { lastSolveTime(unregistered); });
  EXPECT_NE(message.find("'RRTConnect' was not made by the planner registry"), std::string::npos) << message;
}

TEST(PlannerRegistry, RRTConnectSolvesTheThesisProblemWithAValidPath) {
  auto problem = thesisProblem("thesis_obstacle");
  const auto [planner, status] = arcplan::testing::solve(problem, "RRTConnect", {}, 10.0);
  ASSERT_EQ(status, ompl::base::PlannerStatus::EXACT_SOLUTION);
  EXPECT_TRUE(problem.setup->getSolutionPath().check());
}

}  // namespace
