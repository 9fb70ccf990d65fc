#include "campaign_layout.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <vector>

#include "arcplan/benchmarks/benchmark_log_check.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/common/text_parsing.h"
#include "arcplan/planners/planning_problem.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/mesh.h"

namespace arcplan::benchmarks {
namespace detail {
namespace {

nlohmann::json manifestOf(const Suite& suite) {
  nlohmann::json planners = nlohmann::json::array();
  for (const auto& planner : suite.planners) {
    planners.push_back({{"name", planner.label}, {"planner", planner.planner}, {"params", planner.parameters}});
  }
  nlohmann::json problems = nlohmann::json::array();
  for (const auto& problem : suite.problems) problems.push_back(problem.name);
  return {
      {"suite", suite.name},
      {"runs", suite.runs},
      {"time_limit_s", suite.timeLimit},
      {"iteration_budget", suite.iterationBudget ? nlohmann::json(*suite.iterationBudget) : nlohmann::json(nullptr)},
      {"vmax_mps", suite.vMax},
      {"generator_seed", suite.generator ? nlohmann::json(suite.generator->seed) : nlohmann::json(nullptr)},
      {"problems", problems},
      {"planners", planners},
      // Campaigns from before have no such field and are not resumed: their finished jobs drew from
      // seeds per planner, the rest would draw from seeds per problem (docs/reproducibility.md).
      {"seeding", "per problem"}};
}

}  // namespace

std::optional<std::string> jobLogProblem(const std::filesystem::path& out, const Suite& suite, const Job& job) {
  const LogExpectation expected{experimentName(suite, suite.problems[job.problem]), suite.planners[job.planner].label,
                                suite.runs};
  return benchmarkLogProblem(jobLogPath(out, suite, job), expected);
}

void createDirectory(const std::filesystem::path& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw Error("cannot create directory " + directory.string() + ": " + ec.message());
}

void claimOutputDirectory(const std::filesystem::path& directory, const Suite& suite) {
  const auto file = directory / "campaign.json";
  const auto wanted = manifestOf(suite);
  if (std::filesystem::exists(file)) {
    nlohmann::json existing;
    try {
      std::ifstream in(file);
      existing = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      throw Error(file.string() + ": not a campaign description (" + e.what() + "); use another --out");
    }
    // Campaigns started before iteration budgets existed ran without one.
    if (existing.is_object() && !existing.contains("iteration_budget")) existing["iteration_budget"] = nullptr;
    if (existing != wanted) {
      std::vector<std::string> differences;
      for (const auto& [key, value] : wanted.items()) {
        if (!existing.contains(key) || existing[key] != value) differences.push_back(key);
      }
      throw Error(directory.string() + " holds a campaign with other settings (" +
                  (differences.empty() ? std::string("unknown fields") : joinText(differences, ", ")) +
                  " differ from campaign.json); resume with the same suite, --planners, --runs, --time, --budget and "
                  "--vmax, or choose another --out");
    }
    return;
  }
  writeFileAtomically(file, wanted.dump(2) + "\n");
}

std::string jobLabel(const Suite& suite, const Job& job) {
  return suite.problems[job.problem].name + " · " + suite.planners[job.planner].label;
}

std::filesystem::path pathsDirectory(const std::filesystem::path& out, const Suite& suite, const Problem& problem) {
  return out / "paths" / suite.name / problem.name;
}

bool isPlotProblem(const Suite& suite, const Problem& problem) {
  return std::find(suite.plotProblems.begin(), suite.plotProblems.end(), problem.name) != suite.plotProblems.end();
}

JobFiles jobFiles(const std::filesystem::path& out, const Suite& suite, const Job& job) {
  JobFiles files;
  files.log = jobLogPath(out, suite, job);
  const auto& problem = suite.problems[job.problem];
  if (isPlotProblem(suite, problem)) {
    files.medianRun = pathsDirectory(out, suite, problem) / (suite.planners[job.planner].label + ".csv");
  }
  return files;
}

namespace {

// The obstacle as the plots draw it: shape, sizes, pose; a mesh's triangles (obstacle frame, scaled)
// too, since a MoveIt mesh exists only in its scene message and the report must not need the inputs.
nlohmann::json plotObstacle(const collision::Obstacle& obstacle) {
  static const std::map<collision::Obstacle::Shape, const char*> shapes{
      {collision::Obstacle::Shape::Sphere, "sphere"},
      {collision::Obstacle::Shape::Box, "box"},
      {collision::Obstacle::Shape::Cylinder, "cylinder"},
      {collision::Obstacle::Shape::Mesh, "mesh"}};
  const Eigen::Matrix3d r = obstacle.pose.linear();
  const Eigen::Vector3d t = obstacle.pose.translation();
  nlohmann::json json{
      {"name", obstacle.name},
      {"shape", shapes.at(obstacle.shape)},
      {"radius", obstacle.radius},
      {"length", obstacle.length},
      {"size", {obstacle.size.x(), obstacle.size.y(), obstacle.size.z()}},
      {"position", {t.x(), t.y(), t.z()}},
      {"rotation", {{r(0, 0), r(0, 1), r(0, 2)}, {r(1, 0), r(1, 1), r(1, 2)}, {r(2, 0), r(2, 1), r(2, 2)}}}};
  if (obstacle.shape == collision::Obstacle::Shape::Mesh) {
    const auto mesh = obstacle.meshData ? *obstacle.meshData : robot::loadMesh(obstacle.meshFile, obstacle.meshScale);
    std::vector<float> vertices;  // float: the drawing needs no more, and the file stays half the size
    for (const auto& v : mesh.vertices) vertices.insert(vertices.end(), {float(v.x()), float(v.y()), float(v.z())});
    std::vector<int> triangles;
    for (const auto& f : mesh.triangles) triangles.insert(triangles.end(), {f.x(), f.y(), f.z()});
    json["vertices"] = vertices;
    json["triangles"] = triangles;
  }
  return json;
}

// Enough to load the same robot again (robot::loadRobot); empty paths and type: the built-in UR10e.
nlohmann::json plotRobot(const robot::RobotSource& source) {
  nlohmann::json json{{"urdf", source.urdf.string()},
                      {"ur_type", source.urType},
                      {"description", source.description.string()},
                      {"kinematics", source.kinematics.string()},
                      {"base_link", source.chain.baseLink},
                      {"tip_link", source.chain.tipLink},
                      {"tcp_offset", nullptr}};
  if (source.chain.tcpOffset) {
    const Eigen::Vector3d t = source.chain.tcpOffset->translation();
    const Eigen::Quaterniond q(source.chain.tcpOffset->linear());
    json["tcp_offset"] = {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
  }
  return json;
}

}  // namespace

void writePlotScene(const std::filesystem::path& file, const Problem& problem, double vMax) {
  const auto planning =
      planners::makePlanningProblem(std::make_shared<const collision::Scene>(problem.scene), problem.query);
  const auto& robot = planning.collisionModel->robot();
  const auto position = [&](const robot::Vector6& q) {
    const Eigen::Vector3d p = robot::tipPose(robot, q).translation();
    return nlohmann::json{p.x(), p.y(), p.z()};
  };
  nlohmann::json obstacles = nlohmann::json::array();
  for (const auto& obstacle : problem.scene.obstacles) obstacles.push_back(plotObstacle(obstacle));
  nlohmann::json attached = nlohmann::json::array();  // bodies the robot holds, posed in their link's frame
  for (const auto& body : problem.scene.attachedObstacles) {
    attached.push_back(plotObstacle(body.body));
    attached.back()["link"] = body.link;
  }
  // Joints too, so that a report can draw the robot where no planner found a path.
  const auto joints = [](const robot::Vector6& q) { return std::vector<double>(q.data(), q.data() + q.size()); };
  const nlohmann::json scene{{"problem", problem.name},
                             {"robot", plotRobot(problem.scene.robot)},
                             {"obstacles", obstacles},
                             {"attached", attached},
                             {"start", position(planning.start)},
                             {"goal", position(planning.goal)},
                             {"start_joints", joints(planning.start)},
                             {"goal_joints", joints(planning.goal)},
                             {"vmax_mps", vMax}};
  writeFileAtomically(file, scene.dump(1) + "\n");
}

}  // namespace detail

Shard parseShard(const std::string& text) {
  const auto slash = text.find('/');
  const auto fail = [&]() -> Shard {
    throw Error("--shard: '" + text +
                "' is not K/N with whole numbers 1 <= K <= N (e.g. 2/8 for the second of 8 shards)");
  };
  if (slash == std::string::npos) return fail();
  const auto index = parseDouble(text.substr(0, slash)), count = parseDouble(text.substr(slash + 1));
  if (!index || !count || *index != std::floor(*index) || *count != std::floor(*count) || *count < 1 || *index < 1 ||
      *index > *count || *count > 1e6) {
    return fail();
  }
  return {static_cast<int>(*index), static_cast<int>(*count)};
}

std::vector<Job> campaignJobs(const Suite& suite) {
  std::vector<Job> jobs;
  for (std::size_t p = 0; p < suite.problems.size(); ++p) {
    for (std::size_t q = 0; q < suite.planners.size(); ++q) jobs.push_back({p, q});
  }
  return jobs;
}

std::vector<Job> shardJobs(const std::vector<Job>& jobs, const Shard& shard) {
  std::vector<Job> share;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (static_cast<int>(i % static_cast<std::size_t>(shard.count)) + 1 == shard.index) share.push_back(jobs[i]);
  }
  return share;
}

std::string experimentName(const Suite& suite, const Problem& problem) { return suite.name + "/" + problem.name; }

std::filesystem::path jobLogPath(const std::filesystem::path& out, const Suite& suite, const Job& job) {
  return out / "logs" / suite.name / suite.problems[job.problem].name / (suite.planners[job.planner].label + ".log");
}

}  // namespace arcplan::benchmarks
