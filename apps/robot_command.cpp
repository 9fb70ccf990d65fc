// arcplan robot fk|ik|check — kinematics and collision queries on one configuration.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/planners/planning_problem.h"
#include "arcplan/robot/joint_limits.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_inverse_kinematics.h"
#include "cli_support.h"
#include "commands.h"

namespace arcplan::apps {
namespace {

struct RobotOptions {
  RobotSourceOptions robot;
  std::string json;
};

void addRobotOptions(CLI::App& command, RobotOptions& options) {
  addRobotSourceOptions(command, options.robot, "URDF file (default: arcplan's UR10e)");
  command.add_option("--json", options.json, "write the result as JSON to this file ('-' for stdout)");
}

robot::RobotModel loadModel(const RobotOptions& options) { return robot::loadRobot(robotSourceFrom(options.robot)); }

nlohmann::json toJson(const robot::Vector6& q) { return std::vector<double>(q.data(), q.data() + 6); }

void printVector(const robot::Vector6& q) {
  std::cout << std::fixed << std::setprecision(6);
  for (int j = 0; j < 6; ++j) std::cout << (j ? ", " : "") << std::setw(10) << q[j];
  std::cout << "\n";
}

// --joints q0,...: one value per joint of `model`, each inside its limits.
Eigen::VectorXd parseJoints(const robot::RobotModel& model, const std::string& jointText) {
  const auto values = parseVector(jointText, "--joints", static_cast<std::size_t>(model.dof()));
  const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
  if (const auto j = robot::firstJointOutsideLimits(model, q))
    throw UsageError("--joints: " + robot::outsideLimitsText(model, *j, q[*j], "joint " + std::to_string(*j)));
  return q;
}

void runForwardKinematics(const RobotOptions& options, const std::string& jointText) {
  const DropStdout quiet(options.json == "-");
  const auto model = loadModel(options);
  const Eigen::VectorXd q = parseJoints(model, jointText);
  const std::vector<double> values(q.data(), q.data() + q.size());
  const Eigen::Isometry3d pose = robot::tipPose(model, q);
  const auto xyzRpy = robot::xyzRpyFromPose(pose);
  const std::string& tip = model.links()[model.tipLink()].name;
  std::cout << std::fixed << std::setprecision(6) << tip << " in base_link\n"
            << "  position [m]   " << pose.translation().transpose() << "\n"
            << "  rpy [rad]      " << xyzRpy[3] << " " << xyzRpy[4] << " " << xyzRpy[5] << "\n"
            << "  rotation       " << pose.linear().row(0) << "\n"
            << "                 " << pose.linear().row(1) << "\n"
            << "                 " << pose.linear().row(2) << "\n";
  if (!options.json.empty()) {
    nlohmann::json rotation = nlohmann::json::array();
    for (int r = 0; r < 3; ++r) rotation.push_back({pose.linear()(r, 0), pose.linear()(r, 1), pose.linear()(r, 2)});
    writeJson(options.json, {{"link", tip},
                             {"joints", values},
                             {"position", {pose.translation().x(), pose.translation().y(), pose.translation().z()}},
                             {"rotation", rotation},
                             {"rpy", {xyzRpy[3], xyzRpy[4], xyzRpy[5]}}});
  }
}

void runInverseKinematics(const RobotOptions& options, const std::string& poseText, const std::string& seedText) {
  const DropStdout quiet(options.json == "-");
  const auto model = loadModel(options);
  const robot::UrInverseKinematics ik(model);
  const auto values = parseVector(poseText, "--pose", 6);
  const Eigen::Isometry3d target =
      robot::poseFromXyzRpy({values[0], values[1], values[2], values[3], values[4], values[5]});
  const auto solutions = ik.solveAll(target);
  if (solutions.empty()) {
    throw Error("--pose: no inverse-kinematics solution: the pose is out of reach of " + model.name() +
                " or outside its joint limits");
  }
  std::cout << solutions.size() << " solutions inside the joint limits (" << ik.solveBranches(target).size()
            << " analytic branches)\n";
  for (const auto& q : ik.solveBranches(target)) {
    std::cout << "  branch " << ik.branchOf(q) << ": ";
    printVector(q);
  }
  nlohmann::json result{{"pose", values}, {"solutions", nlohmann::json::array()}};
  for (const auto& q : solutions) result["solutions"].push_back(toJson(q));
  if (!seedText.empty()) {
    const auto seedValues = parseVector(seedText, "--seed", 6);
    const robot::Vector6 seed = Eigen::Map<const robot::Vector6>(seedValues.data());
    const auto nearest = ik.solveNearest(target, seed);
    if (!nearest) throw Error("--seed: no solution inside the joint limits");
    std::cout << "nearest to seed: ";
    printVector(*nearest);
    result["nearest"] = toJson(*nearest);
  }
  if (!options.json.empty()) writeJson(options.json, result);
}

struct CheckOptions {
  std::string scene;
  RobotSourceOptions robot;
  std::string joints;
  std::string query;
  std::string json;
};

// A query endpoint as the joints `plan` would start or end at: joints as given (a collision there is
// the check's result), a pose through planners::resolveEndpoint, the one resolver of query poses.
Eigen::VectorXd endpointJoints(const collision::Scene& scene, const collision::Query& query, const std::string& end,
                               const collision::QueryEndpoint& endpoint, const collision::CollisionModel& model) {
  if (endpoint.joints) return *endpoint.joints;
  const robot::UrInverseKinematics ik(model.robot());
  const std::string label = "scene " + scene.sourceFile.string() + ", query '" + query.name + "', " + end;
  return planners::resolveEndpoint(endpoint, model, ik, label);
}

nlohmann::json checkConfiguration(const collision::CollisionModel& model, const Eigen::VectorXd& q) {
  collision::CollisionData data(model);
  const auto report = collision::collide(model, data, q);
  const auto distances = collision::distance(model, data, q);
  const auto finiteOrNull = [](double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
  };
  nlohmann::json collisions = nlohmann::json::array();
  for (const auto& [first, second] : report.collisions) collisions.push_back({first, second});
  std::cout << "  joints        " << std::setprecision(6) << q.transpose() << "\n"
            << "  valid         " << (report.valid ? "yes" : "no (in collision)") << "\n";
  for (const auto& [first, second] : report.collisions)
    std::cout << "  collision     " << first << " - " << second << "\n";
  std::cout << std::fixed << std::setprecision(4);
  if (std::isfinite(distances.obstacleDistance)) {
    std::cout << "  obstacle      " << distances.obstacleDistance << " m (" << distances.obstaclePair.first << " - "
              << distances.obstaclePair.second << ")\n";
  }
  if (std::isfinite(distances.selfDistance)) {
    std::cout << "  self          " << distances.selfDistance << " m (" << distances.selfPair.first << " - "
              << distances.selfPair.second << ")\n";
  }
  // The clearance the state meets (a suite's `clearance` up to it is kept), not the closest pair: self pairs
  // count only below collision::kSelfClearance (docs/collision.md).
  const double clearance = collision::clearanceOf(distances);
  std::cout << "  clearance     " << clearance << " m\n";
  std::cout.unsetf(std::ios::floatfield);
  return {{"joints", std::vector<double>(q.data(), q.data() + q.size())},
          {"valid", report.valid},
          {"collisions", collisions},
          {"clearance_m", finiteOrNull(clearance)},
          {"obstacle_distance_m", finiteOrNull(distances.obstacleDistance)},
          {"obstacle_pair", distances.obstaclePair.first.empty()
                                ? nlohmann::json()
                                : nlohmann::json{distances.obstaclePair.first, distances.obstaclePair.second}},
          {"self_distance_m", finiteOrNull(distances.selfDistance)},
          {"self_pair", distances.selfPair.first.empty()
                            ? nlohmann::json()
                            : nlohmann::json{distances.selfPair.first, distances.selfPair.second}}};
}

void runCollisionCheck(const CheckOptions& options) {
  const DropStdout quiet(options.json == "-");
  if (options.joints.empty() == options.query.empty()) throw UsageError("give exactly one of --joints or --query");
  collision::Scene scene = collision::loadScene(resolveDataPath(options.scene));
  if (options.robot.given()) scene.robot = robotSourceFrom(options.robot);
  const auto model = collision::makeCollisionModel(scene);
  // Every input is checked (and every endpoint solved) before the first line is printed.
  std::vector<std::pair<std::string, Eigen::VectorXd>> configurations;  // (query end or "", joints)
  const collision::Query* query = nullptr;
  if (!options.joints.empty()) {
    configurations.emplace_back("", parseJoints(model->robot(), options.joints));
  } else {
    query = &scene.query(options.query);
    for (const auto& [end, endpoint] : {std::make_pair("start", &query->start), std::make_pair("goal", &query->goal)}) {
      configurations.emplace_back(end, endpointJoints(scene, *query, end, *endpoint, *model));
    }
  }
  std::cout << "scene " << scene.name << " (" << scene.sourceFile.string() << "), " << model->robot().name() << "\n";
  nlohmann::json result{{"scene", scene.name}};
  if (query == nullptr) {
    result.update(checkConfiguration(*model, configurations.front().second));
  } else {
    result["query"] = query->name;
    for (const auto& [end, q] : configurations) {
      std::cout << "query " << query->name << " " << end << "\n";
      result[end] = checkConfiguration(*model, q);
    }
    result["valid"] = result["start"]["valid"].get<bool>() && result["goal"]["valid"].get<bool>();
  }
  if (!options.json.empty()) writeJson(options.json, result);
}

}  // namespace

void registerRobotCommand(CLI::App& app) {
  auto* robotCommand = app.add_subcommand("robot", "kinematics and collision checks of one robot configuration");
  robotCommand->require_subcommand(1);

  auto options = std::make_shared<RobotOptions>();
  auto joints = std::make_shared<std::string>();
  auto* fk = robotCommand->add_subcommand("fk", "forward kinematics: tip pose of a joint vector");
  fk->add_option("--joints", *joints, "joint angles q0,...,q5 [rad]")->required();
  addRobotOptions(*fk, *options);
  fk->callback([options, joints] { runForwardKinematics(*options, *joints); });

  auto pose = std::make_shared<std::string>();
  auto seed = std::make_shared<std::string>();
  auto* ik = robotCommand->add_subcommand("ik", "inverse kinematics: every joint solution of a tip pose");
  ik->add_option("--pose", *pose, "tip pose x,y,z,roll,pitch,yaw [m, rad] in base_link")->required();
  ik->add_option("--seed", *seed, "joint vector; also report the solution nearest to it");
  addRobotOptions(*ik, *options);
  ik->callback([options, pose, seed] { runInverseKinematics(*options, *pose, *seed); });

  auto checkOptions = std::make_shared<CheckOptions>();
  auto* check = robotCommand->add_subcommand(
      "check",
      "collision check of one configuration in a scene: validity, colliding pairs, clearance "
      "(exit code 0 whether or not it collides; non-zero only for bad input)");
  check
      ->add_option("--scene", checkOptions->scene,
                   "scene YAML (a path, or relative to arcplan's data folder, "
                   "e.g. scenes/thesis_obstacle.yaml)")
      ->required();
  addRobotSourceOptions(*check, checkOptions->robot, "robot URDF instead of the scene's robot");
  check->add_option("--joints", checkOptions->joints, "joint angles q0,...,q5 [rad]");
  check->add_option("--query", checkOptions->query,
                    "check the start and goal of this scene query instead "
                    "(poses solved by IK nearest to their seed)");
  check->add_option("--json", checkOptions->json,
                    "write valid, collisions, clearance_m (and distances) as JSON to "
                    "this file ('-' for stdout)");
  check->callback([checkOptions] { runCollisionCheck(*checkOptions); });
}

}  // namespace arcplan::apps
