#pragma once
// Planners by name: the arc planner and OMPL's geometric planners, as ompl::base::PlannerAllocator
// (what SimpleSetup and ompl::tools::Benchmark take), with their parameters settable by name
// ("range" = "0.2") the way `arcplan plan --param` and benchmark suites write them.
#include <ompl/base/Planner.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/scene.h"

namespace arcplan::planners {

// What planners may need besides the SpaceInformation: the arc planner names colliding bodies with
// the collision model and goes around the scene obstacles' bounding balls.
struct PlannerContext {
  std::shared_ptr<const collision::CollisionModel> collisionModel;
  std::vector<collision::Obstacle> obstacles;
};

// Every registered name, "arc" first, then OMPL's planners by class name (RRTConnect, PRMstar, ...).
const std::vector<std::string>& plannerNames();

// The registered spelling of `name` (matching ignores case). Throws arcplan::Error listing the names.
std::string canonicalPlannerName(const std::string& name);

// True for the arc planner, whose path is already a TCP path and must not be shortcut by a path
// simplifier (a shortcut would leave the arc); false for OMPL's planners.
bool isArcPlanner(const std::string& name);

// Throws arcplan::Error for an unknown name (listing the names) or an arc planner without a collision model.
ompl::base::PlannerAllocator plannerAllocator(const std::string& name, const PlannerContext& context);

// The planner's own time for its last solve() call [s], the same measure for every planner the registry makes: the
// call alone, on the steady clock (the arc planner's without its fallback's first-plan simplification, reported apart;
// ArcPlannerResult::solveTime). Each also reports it as its planner data's "solve time REAL", which OMPL's Benchmark
// records per run. OMPL's own `time` counts more: its run thread and, as it calls solve(ptc, 0.1), the wait for the
// thread evaluating the termination condition, which sleeps in 1 ms steps (up to ~1.1 ms). Throws arcplan::Error for a
// planner the registry did not make.
double lastSolveTime(const ompl::base::Planner& planner);

// Allocates the planner and sets its parameters (see setPlannerParameters).
ompl::base::PlannerPtr makePlanner(const std::string& name, const ompl::base::SpaceInformationPtr& si,
                                   const PlannerContext& context,
                                   const std::vector<std::pair<std::string, std::string>>& parameters = {});

// Sets each (name, value) through the planner's ParamSet. Throws arcplan::Error naming the planner
// and parameter: for an unknown parameter (listing the valid ones with their current values) or a
// value the parameter does not accept.
void setPlannerParameters(ompl::base::Planner& planner,
                          const std::vector<std::pair<std::string, std::string>>& parameters);

// A parameter as a planner declares it (ompl::base::ParamSet): its name, default value and range
// suggestion ("low:step:high", or the choices, e.g. "0,1").
struct DeclaredParameter {
  std::string name;
  std::string defaultValue;
  std::string range;
};

// The declared parameters of every registered planner, in plannerNames() order, read from a freshly
// allocated instance of each on `si`.
std::vector<std::pair<std::string, std::vector<DeclaredParameter>>> declaredParameters(
    const ompl::base::SpaceInformationPtr& si, const PlannerContext& context);

// "name=value" -> (name, value); throws arcplan::Error for text without '=' or with an empty side.
std::pair<std::string, std::string> parseParameterAssignment(const std::string& text);

}  // namespace arcplan::planners
