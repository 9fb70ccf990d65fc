// peer_vamp_mbm — arcplan and VAMP side by side on the same MotionBenchMaker problems
// (docs/benchmarks.md, "Side by side with VAMP"). For every problem (a MoveIt scene + request pair)
// it runs, one after the other in one thread: VAMP's RRT-Connect + simplifier with the settings of
// VAMP's own MBM evaluation, arcplan's RRTConnect + OMPL simplifier as `arcplan plan` runs it, and
// arcplan's arc planner. Every path, VAMP's included, is then checked with arcplan's exact meshes
// and certified motion check. Writes JSON (--json) and per-family Markdown tables (stderr,
// --markdown). VAMP (../shared/peers/vamp) is a benchmark peer only: this program is built when it
// is present and nothing of it is part of arcplan.
#include <CLI/CLI.hpp>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <thread>

#include "arcplan/benchmarks/moveit_problems.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "peer_vamp/arcplan_side.h"
#include "peer_vamp/summary.h"

namespace {

using namespace arcplan;
using namespace arcplan::peer_vamp;

const std::string kVamp = "vamp-rrtc";
const std::vector<std::string> kPlanners = {kVamp, "RRTConnect", "arc"};

struct Options {
  std::filesystem::path problems, json, markdown, urdf, srdf;
  double time = 1.0;
  double validationClearance = 1e-5;
  std::uint32_t seed = 1;
  std::size_t perFamily = 0;  // 0: all
};

std::string firstLine(const std::filesystem::path& file, const std::string& prefix) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(prefix, 0) == 0) return line;
  }
  return "";
}

// The benchmark is single-threaded; the load of the machine (other processes) is its caveat.
nlohmann::json machine(const std::string& when) {
  std::string model = firstLine("/proc/cpuinfo", "model name");
  if (const auto colon = model.find(": "); colon != std::string::npos) model = model.substr(colon + 2);
  return {{"cpu", model},
          {"hardware_threads", std::thread::hardware_concurrency()},
          {"benchmark_threads", 1},
          {"loadavg_" + when, firstLine("/proc/loadavg", "")}};
}

Joints jointsOf(const std::optional<robot::Vector6>& q, const std::string& what) {
  if (!q) throw Error(what + " is not given as joints");
  Joints joints{};
  for (int j = 0; j < 6; ++j) joints[j] = (*q)[j];
  return joints;
}

void checkJointOrder(const robot::RobotModel& model) {
  const VampRobotInfo vamp = vampRobotInfo();
  for (std::size_t j = 0; j < vamp.jointNames.size(); ++j) {
    if (static_cast<int>(j) >= model.dof() || model.joints()[j].name != vamp.jointNames[j]) {
      throw Error("the URDF's joint " + std::to_string(j) + " is not VAMP's " + vamp.jointNames[j] +
                  ": VAMP's compiled UR5 does not match this robot");
    }
  }
}

// Fills the exact-check fields of a solved outcome.
void certify(Outcome& outcome, const std::vector<Joints>& path, const collision::CollisionModel& model,
             const Joints& start, const Joints& goal, const Options& options) {
  outcome.waypoints = path.size();
  outcome.pathCost = pathLength(path);
  outcome.pathStart = path.front();
  outcome.pathEnd = path.back();
  const PathCheck check = checkPathExactly(model, path, start, goal, options.validationClearance);
  outcome.validExact = check.valid;
  outcome.exactFailure = check.firstFailure;
  outcome.certificationUs = check.certificationUs;
  outcome.startError = check.startError;
  outcome.goalError = check.goalError;
}

struct Run {
  std::map<std::string, std::vector<Outcome>> outcomes;
  nlohmann::json problems = nlohmann::json::array();
  FrameDifference robotDifference;
};

void runProblem(const benchmarks::MoveItProblemFiles& files, const collision::MoveItRobot& robot,
                const Options& options, Run& run) {
  const collision::MoveItProblem loaded = collision::loadMoveItProblem(files.scene, files.request, robot);
  const collision::Query& query = loaded.scene.queries.at(0);
  const Joints start = jointsOf(query.start.joints, files.request.string() + ": start");
  const Joints goal = jointsOf(query.goal.joints, files.request.string() + ": goal");
  const auto scene = std::make_shared<const collision::Scene>(loaded.scene);
  const auto model = collision::makeCollisionModel(*scene);
  collision::CollisionData data(*model);
  checkJointOrder(model->robot());
  for (const Joints& q : {start, goal}) {
    const FrameDifference d =
        endEffectorDifference(model->robot(), loaded.baseInPlanningFrame, vampRobotInfo().endEffector, q);
    run.robotDifference.position = std::max(run.robotDifference.position, d.position);
    run.robotDifference.rotation = std::max(run.robotDifference.rotation, d.rotation);
  }
  const collision::CollisionReport startReport =
      collision::collide(*model, data, Eigen::Map<const robot::Vector6>(start.data()));
  const collision::CollisionReport goalReport =
      collision::collide(*model, data, Eigen::Map<const robot::Vector6>(goal.data()));

  Outcome base;
  base.family = files.family;
  base.problem = files.name;
  std::map<std::string, Outcome> outcome;

  // VAMP.
  const VampRun vamp = runVamp(toVampScene(loaded, cylindersAsCuboids(files.family)), start, goal, VampSettings{});
  Outcome& v = outcome[kVamp] = base;
  v.inputsValid = vamp.startValid && vamp.goalValid;
  v.solved = vamp.solved;
  v.planningUs = vamp.planningUs;
  v.simplificationUs = vamp.simplificationUs;
  v.totalUs = vamp.planningUs + vamp.simplificationUs;
  v.wallUs = vamp.wallUs;
  if (!v.inputsValid) {
    v.reason = "start or goal invalid under VAMP's spheres: not planned (VAMP's evaluation skips such problems)";
  } else if (!vamp.solved) {
    v.reason = "no path within " + std::to_string(VampSettings{}.maxIterations) + " iterations";
  } else {
    certify(v, vamp.path, *model, start, goal, options);
  }

  // arcplan, when the exact model accepts the start and goal (makePlanningProblem refuses otherwise).
  const bool exactInputs = startReport.valid && goalReport.valid;
  std::optional<planners::PlanningProblem> planning;
  std::string refusal = "start or goal in collision under the exact meshes";
  if (exactInputs) {
    try {
      planning = planners::makePlanningProblem(scene);
    } catch (const Error& error) {
      refusal = error.what();
    }
  }
  for (const std::string& name : {std::string("RRTConnect"), std::string("arc")}) {
    Outcome& o = outcome[name] = base;
    o.inputsValid = exactInputs;
    if (!planning) {
      o.reason = refusal;
      continue;
    }
    const PlannerRun result = runArcplanPlanner(*planning, name, sameRangeAsVamp(name), options.time);
    o.solved = result.solved;
    o.reason = result.reason;
    o.planningUs = result.planningUs;
    o.simplificationUs = result.simplificationUs;
    o.totalUs = result.totalUs;
    o.mode = result.mode;
    if (result.solved) certify(o, result.path, *model, start, goal, options);
  }

  run.problems.push_back({{"family", files.family},
                          {"problem", files.name},
                          {"start_valid_exact", startReport.valid},
                          {"goal_valid_exact", goalReport.valid},
                          {"start_collisions", collision::describeCollisions(startReport)},
                          {"goal_collisions", collision::describeCollisions(goalReport)},
                          {"start_valid_vamp", vamp.startValid},
                          {"goal_valid_vamp", vamp.goalValid}});
  for (const std::string& name : kPlanners) run.outcomes[name].push_back(outcome[name]);
}

std::string progressLine(const Run& run) {
  std::ostringstream line;
  const Outcome& first = run.outcomes.at(kVamp).back();
  line << first.family << "/" << first.problem << ":";
  for (const std::string& name : kPlanners) {
    const Outcome& o = run.outcomes.at(name).back();
    line << "  " << name << " ";
    if (o.solved) {
      line << static_cast<long>(o.totalUs) << " us" << (o.validExact ? "" : " (path NOT valid under exact meshes)");
    } else {
      line << (o.inputsValid ? "failed" : "invalid input");
    }
  }
  return line.str();
}

nlohmann::json settingsJson(const Options& options) {
  const VampRobotInfo vamp = vampRobotInfo();
  const VampSettings settings;
  return {{"vamp",
           {{"robot", vamp.name},
            {"end_effector", vamp.endEffector},
            {"spheres", vamp.spheres},
            {"rake", vamp.rake},
            {"resolution", vamp.resolution},
            {"rrtc_range", settings.range},
            {"rrtc_max_iterations", settings.maxIterations},
            {"simplify", "SimplifySettings defaults"},
            {"sampler", "Halton, reset per problem"},
            {"total_us", "VAMP's own timers: planning + simplification"},
            {"wall_us", "steady_clock around both calls (includes VAMP's per-call buffer allocation)"}}},
          {"arcplan",
           {{"time_limit_s", options.time},
            {"seed", options.seed},
            {"motion_check", "certified"},
            {"rrtconnect_range", settings.range},
            {"arc_fallback_range", settings.range},
            {"total_us", "steady_clock around SimpleSetup::solve and simplifySolution"}}},
          {"exact_check", {{"method", "certified"}, {"minimum_clearance_m", options.validationClearance}}}};
}

void run(const Options& options) {
  ompl::RNG::setSeed(options.seed);  // process-global, before any planner exists
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  // MBM's layout: mbm_ur5/{ur5.urdf, ur5.srdf, problems/<family>/...}; a family folder may be given.
  std::filesystem::path data = options.problems.parent_path();
  if (!std::filesystem::exists(data / "ur5.urdf")) data = data.parent_path();
  collision::MoveItRobot robot{options.urdf.empty() ? data / "ur5.urdf" : options.urdf,
                               options.srdf.empty() ? data / "ur5.srdf" : options.srdf};
  if (options.srdf.empty() && !std::filesystem::exists(robot.srdf)) robot.srdf.clear();

  std::vector<benchmarks::MoveItProblemFiles> files = benchmarks::listMoveItProblems(options.problems);
  if (options.perFamily > 0) {
    std::map<std::string, std::size_t> taken;
    files.erase(std::remove_if(files.begin(), files.end(),
                               [&](const auto& f) { return ++taken[f.family] > options.perFamily; }),
                files.end());
  }
  nlohmann::json document = {{"program", "peer_vamp_mbm"},
                             {"problems_folder", options.problems.string()},
                             {"urdf", robot.urdf.string()},
                             {"settings", settingsJson(options)},
                             {"machine", machine("start")}};
  Run results;
  for (std::size_t i = 0; i < files.size(); ++i) {
    runProblem(files[i], robot, options, results);
    std::cerr << "[" << i + 1 << "/" << files.size() << "] " << progressLine(results) << "\n";
  }
  document["machine"].update(machine("end"));
  document["robot_check"] = {{"link", vampRobotInfo().endEffector},
                             {"configurations", 2 * files.size()},
                             {"max_position_difference_m", results.robotDifference.position},
                             {"max_rotation_difference_rad", results.robotDifference.rotation}};
  document["problems"] = results.problems;
  for (const std::string& name : kPlanners) document["planners"][name] = plannerJson(results.outcomes[name]);

  const std::string tables = markdownTables(results.outcomes, kPlanners);
  std::cerr << "\n" << tables;
  if (!options.markdown.empty()) writeFileAtomically(options.markdown, tables);
  writeFileAtomically(options.json, document.dump(1) + "\n");
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{
      "Runs VAMP's RRT-Connect and arcplan's RRTConnect and arc planners on the same MotionBenchMaker "
      "problems (MoveIt scene + request pairs) and checks every path with arcplan's exact meshes.",
      "peer_vamp_mbm"};
  app.add_option("--problems", options.problems,
                 "folder of sceneNNNN.yaml/requestNNNN.yaml pairs, directly or one family folder deep")
      ->required()
      ->check(CLI::ExistingDirectory);
  app.add_option("--json", options.json, "JSON result file")->required();
  app.add_option("--markdown", options.markdown, "also write the per-family tables as Markdown here");
  app.add_option("--urdf", options.urdf, "robot URDF (default: ur5.urdf next to the problems folder)");
  app.add_option("--srdf", options.srdf, "robot SRDF (default: ur5.srdf next to the problems folder, if present)");
  app.add_option("--time", options.time, "arcplan planners' time limit per problem [s]")->check(CLI::PositiveNumber);
  app.add_option("--seed", options.seed, "OMPL's random seed (VAMP's Halton sequence needs none)");
  app.add_option("--per-family", options.perFamily, "only the first N problems of each family (0: all)");
  app.add_option("--exact-clearance", options.validationClearance,
                 "the certified check's minimum clearance when paths are validated [m]")
      ->check(CLI::Range(1e-5, 1.0));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help exits 0; a wrong command line exits 2, as `arcplan` does (docs/cli.md).
    return app.exit(error) == 0 ? 0 : 2;
  }
  options.problems = std::filesystem::absolute(options.problems).lexically_normal();
  if (!options.problems.has_filename()) options.problems = options.problems.parent_path();  // "DIR/"
  try {
    run(options);
  } catch (const std::exception& error) {
    std::cerr << "peer_vamp_mbm: error: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
