// arcplan plan — solve one scene query with the arc planner or an OMPL planner (docs/cli.md): status,
// reason, the metrics of docs/metrics.md of the path, and the joint path as CSV.
#include <ompl/util/Console.h>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "arcplan/benchmarks/moveit_problems.h"
#include "arcplan/benchmarks/plan_query.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/collision/ompl_validity.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/planners/arc_planner.h"
#include "arcplan/planners/planner_registry.h"
#include "arcplan/planners/planning_problem.h"
#include "arcplan/trajectory/joint_path.h"
#include "arcplan/trajectory/metric_descriptors.h"
#include "cli_support.h"
#include "commands.h"

namespace arcplan::apps {
namespace {

struct PlanOptions {
  std::string scene;
  std::string moveitScene, moveitRequest, srdf;  // a MoveIt problem instead of --scene
  RobotSourceOptions robot;                      // its robot: --urdf, --tip, --tcp-offset
  std::string query;
  std::string planner = "arc";
  std::vector<std::string> parameters;
  double time = 5.0;
  std::optional<std::uint32_t> seed;
  std::optional<double> maxTcpSpeed;
  double clearance = 0.0;
  std::string json;
  std::string pathCsv;
  bool allowApproximate = false;
  bool verbose = false;
};

// The planner parameters for --help, read from the planners themselves (the arc planner on the
// robot with no obstacles). OMPL's log is off meanwhile: reading BITstar's and ABITstar's deprecated
// options warns on stderr, and --help prints the help only.
std::string plannerParameterHelp() {
  const auto model = collision::makeCollisionModel(collision::Scene{});
  const auto si = collision::makeSpaceInformation(model);
  const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  const auto declared = planners::declaredParameters(si, {model, {}});
  ompl::msg::setLogLevel(level);
  std::ostringstream text;
  text << "Planner parameters (--param NAME=VALUE; default, declared range):\n";
  for (const auto& [planner, parameters] : declared) {
    text << "  " << planner << ":";
    if (parameters.empty()) text << " (none)";
    for (const auto& parameter : parameters) {
      text << " " << parameter.name << "=" << parameter.defaultValue;
      if (!parameter.range.empty()) text << " [" << parameter.range << "]";
    }
    text << "\n";
  }
  return text.str();
}

// A metric's value in the result document, under its key from the metric table.
const nlohmann::json& metricOf(const nlohmann::json& document, double trajectory::TrajectoryMetrics::*member) {
  return document[trajectory::metricDescriptor(member).key];
}

void printSummary(const nlohmann::json& document, const benchmarks::PlannedQuery& planned) {
  const std::string& reason = planned.reason;
  const std::optional<planners::ArcPlannerResult>& arc = planned.arc;
  const std::size_t waypoints = planned.path.size();
  using M = trajectory::TrajectoryMetrics;
  std::cout << "plan: scene " << document["scene"].get<std::string>() << ", query "
            << document["query"].get<std::string>() << ", planner " << document["planner"].get<std::string>() << "\n"
            << "status              " << document["status"].get<std::string>() << "\n";
  if (!reason.empty()) std::cout << "reason              " << reason << "\n";
  std::cout << std::setprecision(6) << "solve time          "
            << document[trajectory::solveTimeDescriptor().key].get<double>() << " s\n";
  if (arc && !arc->mode().empty()) {
    std::cout << "mode                " << arc->mode() << " (cartesian fraction " << arc->cartesianFraction << ")\n";
    if (const auto why = planned.fallbackReason()) std::cout << "fallback reason     " << *why << "\n";
    for (std::size_t i = 0; i < arc->viaPoints.size(); ++i) {
      const Eigen::Vector3d& point = arc->viaPoints[i];
      std::cout << "via point           (" << point.x() << ", " << point.y() << ", " << point.z() << ") m, blend "
                << arc->blends[i] << " m\n";
    }
  }
  if (arc) {
    for (const planners::Detour& detour : arc->detours) {
      std::cout << "arc detour          O at " << detour.position << " m: h " << detour.shape.sagitta << ", r "
                << detour.shape.halfChord << ", R2 " << detour.shape.entryRadius << ", R3 " << detour.shape.exitRadius
                << " m, plane " << detour.planeAngle << " rad\n";
    }
  }
  if (waypoints > 0) {
    std::cout << "waypoints           " << waypoints << "\n"
              << "tcp path length     " << metricOf(document, &M::tcpPathLength).get<double>() << " m\n"
              << "joint path length   " << metricOf(document, &M::jointPathLength).get<double>() << " rad\n";
    if (!metricOf(document, &M::minClearance).is_null()) {
      std::cout << "min clearance       " << metricOf(document, &M::minClearance).get<double>() << " m\n";
    }
    if (planned.options.clearance > 0.0) {
      std::cout << "clearance           " << planned.options.clearance << " m "
                << (document["clearance_kept"].get<bool>() ? "kept" : "NOT kept") << " (approach zones as bench)\n";
    }
    if (planned.options.maxTcpSpeed) {
      std::cout << "execution time      " << metricOf(document, &M::executionTime).get<double>() << " s at vmax "
                << *planned.options.maxTcpSpeed << " m/s (peak TCP speed "
                << metricOf(document, &M::peakTcpSpeed).get<double>() << " m/s)\n";
    }
  }
}

// The scene and query to plan: --scene (and --query), or a MoveIt scene + request read against --urdf
// or --ur-type.
std::shared_ptr<const collision::Scene> loadPlanScene(const PlanOptions& options) {
  const bool moveit = !options.moveitScene.empty() || !options.moveitRequest.empty();
  if (moveit == !options.scene.empty())
    throw UsageError("give either --scene or --moveit-scene with --moveit-request (and --urdf or --ur-type)");
  if (!moveit) {
    if (options.robot.given() || !options.srdf.empty())
      throw UsageError("the robot options and --srdf go with --moveit-scene (a scene file names its robot)");
    return std::make_shared<const collision::Scene>(collision::loadScene(resolveDataPath(options.scene)));
  }
  if (options.moveitScene.empty() || options.moveitRequest.empty() ||
      (options.robot.urdf.empty() && options.robot.urType.empty()))
    throw UsageError("--moveit-scene needs --moveit-request and --urdf or --ur-type");
  if (!options.query.empty()) throw UsageError("--query names a query of --scene; a MoveIt request is one query");
  const robot::RobotSource source = robotSourceFrom(options.robot);
  auto problem =
      collision::loadMoveItProblem(options.moveitScene, options.moveitRequest,
                                   {source.urdf, options.srdf, {source.urType, source.description, source.kinematics}});
  problem.scene.robot.chain = source.chain;  // the TCP the arc planner moves along lines
  for (const auto& name : problem.ignoredMatrixNames) {
    std::cerr << "arcplan: note: allowed_collision_matrix name '" << name
              << "' is no link of the robot (--urdf or --ur-type) and no object; ignored (the matrix names every link, "
                 "as MoveIt exports it)\n";
  }
  return std::make_shared<const collision::Scene>(std::move(problem.scene));
}

// MoveIt problems come with their own start and goal: an invalid one is reported (JSON start_valid /
// goal_valid and the pairs in contact) and not planned.
void checkMoveItEndpoints(const collision::Scene& scene, const PlanOptions& options, nlohmann::json& validity) {
  if (options.moveitScene.empty()) return;
  const benchmarks::ProblemValidity checked = benchmarks::checkEndpoints(scene);
  validity = {{"start_valid", checked.start.valid}, {"goal_valid", checked.goal.valid}};
  if (checked.valid()) return;
  std::string why;
  for (const auto& [end, check] : {std::pair{"start", &checked.start}, std::pair{"goal", &checked.goal}}) {
    if (check->valid) continue;
    validity[std::string(end) + "_problem"] = check->problem;
    why += (why.empty() ? "" : "; ") + std::string(end) + " " + check->problem;
  }
  if (!options.json.empty()) {
    nlohmann::json document = {{"scene", scene.name},
                               {"query", scene.queries.front().name},
                               {"planner", planners::canonicalPlannerName(options.planner)},
                               {"status", "invalid"}};
    document.update(validity);
    writeJson(options.json, document);
  }
  throw Error("MoveIt problem " + scene.sourceFile.string() + " not planned: " + why);
}

void runPlan(const PlanOptions& options) {
  const DropStdout quiet(options.json == "-");
  ompl::msg::setLogLevel(options.verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
  benchmarks::PlanQueryOptions request;
  for (const std::string& text : options.parameters)
    request.parameters.push_back(planners::parseParameterAssignment(text));
  request.planner = planners::canonicalPlannerName(options.planner);
  request.timeLimit = options.time;
  request.seed = options.seed;
  request.maxTcpSpeed = options.maxTcpSpeed;
  request.clearance = options.clearance;
  try {  // the library's check, before anything is read: a bad value is a wrong command line
    benchmarks::checkPlanQueryOptions(request, {"--time", "--vmax", "--clearance"});
  } catch (const Error& e) {
    throw UsageError(e.what());
  }

  const auto scene = loadPlanScene(options);
  nlohmann::json validity;
  checkMoveItEndpoints(*scene, options, validity);
  const benchmarks::PlannedQuery planned = benchmarks::planQuery(scene, options.query, request);
  nlohmann::json document = benchmarks::toJson(planned);
  if (!validity.is_null()) document.update(validity);
  const std::string& plannerName = planned.options.planner;
  const std::string& reason = planned.reason;
  const bool haveExact = planned.status == benchmarks::PlanStatus::Exact;
  const bool havePath = !planned.path.empty();

  // With the JSON on stdout, the summary would corrupt it.
  if (options.json != "-") printSummary(document, planned);
  if (!options.json.empty()) writeJson(options.json, document);
  // A path closer than --clearance somewhere is what bench counts as not solved: neither written nor exit 0.
  if (havePath && !planned.clearanceKept) {
    throw Error("planner " + plannerName + "'s path does not keep the clearance of " +
                std::to_string(options.clearance) + " m: it comes " + std::to_string(-planned.clearanceMargin) +
                " m closer somewhere (the judgement bench counts as not solved); no path written");
  }
  // An approximate path ends away from the goal: only written when asked for.
  const bool acceptedPath = haveExact || (havePath && options.allowApproximate);
  if (!options.pathCsv.empty() && acceptedPath) trajectory::writeJointPathCsv(options.pathCsv, planned.path);
  if (!haveExact) {
    if (havePath && options.allowApproximate) {
      std::cerr << "arcplan: warning: " << plannerName << " returned an approximate path: " << reason << "\n";
      return;
    }
    if (havePath) {
      throw Error("planner " + plannerName +
                  " found only an approximate path (--allow-approximate accepts it): " + reason);
    }
    throw Error("planner " + plannerName + " found no path: " + reason);
  }
}

}  // namespace

void registerPlanCommand(CLI::App& app) {
  auto options = std::make_shared<PlanOptions>();
  CLI::App* command = app.add_subcommand("plan", "plan a scene query with the arc planner or an OMPL planner");
  command->footer(
      "Solves a scene query with the arc planner (thesis ch. 3) or an OMPL planner; reports status, reason, "
      "solve time, TCP/joint path length and clearance; writes the joint path.");
  command->footer(plannerParameterHelp);
  command->add_option("--scene", options->scene,
                      "scene YAML (a path, or a name under data/, e.g. scenes/thesis_obstacle.yaml)");
  command->add_option("--moveit-scene", options->moveitScene,
                      "instead of --scene: a moveit_msgs/PlanningScene YAML or an RViz .scene file (with "
                      "--moveit-request and --urdf or --ur-type)");
  command->add_option("--moveit-request", options->moveitRequest,
                      "the moveit_msgs/MotionPlanRequest YAML to plan in --moveit-scene");
  addRobotSourceOptions(*command, options->robot, "the robot of the MoveIt problem (URDF; joint and link names)");
  command->add_option("--srdf", options->srdf, "its SRDF (disabled collision pairs), optional");
  command->add_option("--query", options->query, "query name in the scene (default: the first)");
  command
      ->add_option("--planner", options->planner,
                   "planner: arc, RRTConnect, RRT, RRTstar, PRM, PRMstar, LazyPRM, BKPIECE1, KPIECE1, EST, SBL, "
                   "BiTRRT, InformedRRTstar, BITstar, ... (case-insensitive)")
      ->capture_default_str();
  command->add_option("--param", options->parameters,
                      "planner parameter NAME=VALUE, repeatable; each planner's parameters are listed below");
  command->add_option("--time", options->time, "time limit for solving [s]")->capture_default_str();
  command->add_option("--seed", options->seed,
                      "seed of OMPL's random numbers, for reproducible sampling planners (set once per process)");
  command->add_option(
      "--vmax", options->maxTcpSpeed,
      "also time-scale the path (PCHIP) under this TCP speed limit [m/s] and report the scaled metrics");
  command
      ->add_option("--clearance", options->clearance,
                   "distance every state and motion keeps from obstacles (own links: at most 1 mm) [m], relaxed near a "
                   "start or goal closer than that as bench does (docs/collision.md); the JSON says whether the "
                   "path kept it")
      ->capture_default_str();
  command->add_option("--json", options->json, "write the result as JSON to this file ('-' for stdout)");
  command->add_option("--path-csv", options->pathCsv, "write the joint path (q0..q5 per waypoint) as CSV");
  command->add_flag("--allow-approximate", options->allowApproximate,
                    "accept an approximate path (one that ends away from the goal): exit 0 and write its CSV");
  addCollisionModeOption(*command);
  command->add_flag("--verbose", options->verbose, "show OMPL's informational messages");
  command->callback([options] { runPlan(*options); });
}

}  // namespace arcplan::apps
