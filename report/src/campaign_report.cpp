#include "arcplan/report/campaign_report.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <optional>

#include "arcplan/benchmarks/benchmark_database.h"
#include "arcplan/benchmarks/median_run.h"
#include "arcplan/benchmarks/ranking.h"
#include "arcplan/common/error.h"
#include "arcplan/report/robot_animation.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/robot_source.h"
#include "plot_scene.h"
#include "compact_number.h"
#include "json_file.h"

namespace arcplan::report {
namespace {

constexpr std::size_t kLongText = 200;

std::string relativeLink(const std::filesystem::path& target, const std::filesystem::path& output) {
  const auto from = std::filesystem::weakly_canonical(std::filesystem::absolute(output)).parent_path();
  return std::filesystem::weakly_canonical(std::filesystem::absolute(target)).lexically_relative(from).generic_string();
}

nlohmann::json runsJson(const benchmarks::BenchmarkDatabase& runs) {
  nlohmann::json problems = nlohmann::json::object();
  for (const auto& [problem, planners] : runs.runs) {
    for (const auto& [planner, plannerRuns] : planners) {
      nlohmann::json entry{{"solved", nlohmann::json::array()}, {"values", nlohmann::json::object()}};
      for (const auto& attribute : runs.attributes) entry["values"][attribute.key] = nlohmann::json::array();
      for (const auto& run : plannerRuns) {
        entry["solved"].push_back(run.solved ? 1 : 0);
        for (const auto& attribute : runs.attributes) {
          const auto found = run.values.find(attribute.key);
          entry["values"][attribute.key].push_back(found != run.values.end() && std::isfinite(found->second)
                                                       ? nlohmann::json(found->second)
                                                       : nlohmann::json(nullptr));
        }
      }
      problems[problem][planner] = std::move(entry);
    }
  }
  return problems;
}

// Frames of the arm when `robot` is given (null: the run has no joints or the robot did not load).
nlohmann::json medianRunJson(const benchmarks::MedianRun& run, const robot::RobotModel* robot,
                             const CampaignReportOptions& options) {
  nlohmann::json t = nlohmann::json::array(), speed = nlohmann::json::array(), tcp = nlohmann::json::array();
  const auto keep = [&](std::size_t i) {
    t.push_back(detail::withSignificantDigits(run.time[i], 6));
    speed.push_back(detail::withSignificantDigits(run.tcpSpeed[i], 5));
    for (int k = 0; k < 3; ++k) tcp.push_back(detail::withSignificantDigits(run.tcp[i][k], 5));
  };
  const std::size_t n = run.time.size();
  const std::size_t stride = std::max<std::size_t>(1, (n + options.profileSamples - 1) / options.profileSamples);
  for (std::size_t i = 0; i < n; i += stride) keep(i);
  if ((n - 1) % stride != 0) keep(n - 1);
  nlohmann::json entry{{"name", run.planner}, {"t", t}, {"speed", speed}, {"tcp", tcp}, {"notes", run.notes}};
  entry["frames"] =
      robot ? linkPoseFrames(*robot, run.time, run.joints, options.animationRate) : nlohmann::json(nullptr);
  return entry;
}

// The robots of the plot problems, each loaded and drawn once (a campaign usually has one). A robot
// that no longer loads (its URDF moved) costs the pages their arm, not the report.
class PlotRobots {
public:
  // Index of the scene's robot; nullopt, with a note in `missing`, when it cannot be loaded.
  std::optional<std::size_t> indexOf(const nlohmann::json& scene, nlohmann::json& missing) {
    const auto key = scene.contains("robot") ? scene["robot"].dump() : std::string("ur10e");
    const auto found = std::find(keys_.begin(), keys_.end(), key);
    const auto index = static_cast<std::size_t>(found - keys_.begin());
    if (found == keys_.end()) {
      keys_.push_back(key);
      used_.push_back(false);
      const auto noArm = [&](const std::string& why) {
        models_.emplace_back(std::nullopt);
        missing.push_back("The robot of " + scene.value("problem", std::string("a plot problem")) +
                          " cannot be loaded (" + why + "): its 3D views show no arm.");
      };
      try {
        models_.emplace_back(robot::loadRobot(detail::robotSourceOf(scene)));
      } catch (const Error& error) {
        noArm(error.what());
      } catch (const nlohmann::json::exception& error) {  // a malformed "robot" entry
        noArm(error.what());
      }
    }
    return models_[index] ? std::optional<std::size_t>(index) : std::nullopt;
  }
  const robot::RobotModel& model(std::size_t index) const { return *models_[index]; }
  const robot::RobotModel& use(std::size_t index) {
    used_[index] = true;
    return *models_[index];
  }
  // [{name, meshes}] per robot some page moves an arm of (null for the others).
  nlohmann::json json() const {
    nlohmann::json robots = nlohmann::json::array();
    for (std::size_t i = 0; i < models_.size(); ++i) {
      robots.push_back(used_[i] ? nlohmann::json{{"name", models_[i]->name()}, {"meshes", robotMeshesJson(*models_[i])}}
                                : nlohmann::json(nullptr));
    }
    return robots;
  }

private:
  std::vector<std::string> keys_;
  std::vector<bool> used_;
  std::deque<std::optional<robot::RobotModel>> models_;
};

// Speed profiles, TCP paths, obstacles and arm frames of every problem with a paths/ folder; the
// robots they use in data["robots"].
nlohmann::json pathsJson(const std::filesystem::path& campaign, const benchmarks::BenchmarkDatabase& runs,
                         const CampaignReportOptions& options, nlohmann::json& data) {
  nlohmann::json paths = nlohmann::json::object();
  auto& missing = data["missing"];
  PlotRobots robots;
  std::vector<std::string> withoutJoints;
  for (const auto& [problem, planners] : runs.runs) {
    const auto folder = campaign / "paths" / problem;
    if (!std::filesystem::exists(folder / "scene.json")) continue;
    const auto sceneFile = folder / "scene.json";
    const auto scene = detail::readJsonFile(sceneFile);
    const auto robot = robots.indexOf(scene, missing);
    nlohmann::json entry;
    try {
      entry = {{"scene", detail::drawnScene(scene, robot ? &robots.model(*robot) : nullptr)},
               {"robot", robot ? nlohmann::json(*robot) : nlohmann::json(nullptr)},
               {"planners", nlohmann::json::array()}};
      if (robot && scene.contains("start_joints") && scene.contains("goal_joints")) {
        // Frame 0 the start, frame 1 the goal: the arm is drawn even where no planner found a path.
        entry["endpoints"] =
            linkPoseFrames(robots.use(*robot), {0.0, 1.0},
                           {detail::jointsOf(scene, "start_joints"), detail::jointsOf(scene, "goal_joints")}, 1.0);
      }
    } catch (const nlohmann::json::exception& error) {  // a key of the wrong type or missing: name the file
      throw Error(sceneFile.string() + ": " + error.what());
    }
    for (const auto& [planner, plannerRuns] : planners) {
      const auto file = folder / (planner + ".csv");
      if (!std::filesystem::exists(file)) continue;  // no successful run: nothing to draw
      const auto run = benchmarks::readMedianRun(file);
      if (run.joints.empty()) withoutJoints.push_back(file.string());
      entry["planners"].push_back(
          medianRunJson(run, robot && !run.joints.empty() ? &robots.use(*robot) : nullptr, options));
    }
    paths[problem] = std::move(entry);
  }
  data["robots"] = robots.json();
  if (paths.empty()) {
    missing.push_back("No path data: " + (campaign / "paths").string() +
                      " has no scene.json for any problem, so there are no speed profiles and no 3D views "
                      "(a campaign writes them for the suite's plot problems).");
  }
  if (!withoutJoints.empty()) {
    missing.push_back("No joint columns (q0..q5) in " + std::to_string(withoutJoints.size()) +
                      " median-run file(s), e.g. " + withoutJoints.front() +
                      ": the 3D view shows their TCP paths but cannot move the arm along them.");
  }
  return paths;
}

}  // namespace

nlohmann::json campaignReportData(const std::filesystem::path& input, const std::filesystem::path& output,
                                  const CampaignReportOptions& options) {
  const bool isFolder = std::filesystem::is_directory(input);
  const auto database = isFolder ? input / "benchmark.db" : input;
  const auto campaign = database.parent_path().empty() ? std::filesystem::path(".") : database.parent_path();
  const auto runs = benchmarks::readBenchmarkDatabase(database);

  nlohmann::json data{{"kind", "campaign"}, {"missing", nlohmann::json::array()}};
  auto& missing = data["missing"];
  data["source"] = {{"campaign", campaign.string()}, {"database", database.string()}};
  data["links"] = nlohmann::json::array();
  const auto link = [&](const std::string& label, const std::filesystem::path& target) {
    if (std::filesystem::exists(target))
      data["links"].push_back({{"label", label}, {"href", relativeLink(target, output)}});
  };
  link("benchmark database (SQLite, Planner Arena)", database);
  link("OMPL benchmark logs", campaign / "logs");
  link("ranking (Markdown)", campaign / "ranking.md");
  link("ranking (CSV)", campaign / "ranking.csv");
  link("ranking (JSON)", campaign / "ranking.json");
  link("campaign settings", campaign / "campaign.json");

  // The experiments' long texts (OMPL's setup dump, /proc/cpuinfo) would outweigh the plots: first lines only.
  auto experiments = runs.experiments;
  for (auto& experiment : experiments) {
    for (auto item : experiment.items()) {
      auto& value = item.value();
      if (!value.is_string() || value.get<std::string>().size() <= kLongText) continue;
      const auto text = value.get<std::string>();
      value = text.substr(0, std::min(kLongText, text.find('\n')));
    }
  }
  data["settings"] = {{"campaign", std::filesystem::exists(campaign / "campaign.json")
                                       ? detail::readJsonFile(campaign / "campaign.json")
                                       : nlohmann::json(nullptr)},
                      {"experiments", experiments}};
  data["attributes"] = nlohmann::json::array();
  for (const auto& attribute : runs.attributes)
    data["attributes"].push_back({{"key", attribute.key}, {"label", attribute.label}});
  data["runs"] = runsJson(runs);
  data["arcplan_columns"] = runs.arcplanColumns;
  if (runs.arcplanColumns) {
    auto ranking = benchmarks::rankRuns(runs.runs, runs.families);
    ranking.database = database;
    data["ranking"] = benchmarks::rankingJson(ranking);
  } else {
    data["ranking"] = nullptr;
    missing.push_back(
        database.string() +
        " has no arcplan columns (execution_time, tcp_path_length, ...): a plain OMPL database, so there is "
        "no ranking by execution time — the tables count successes and the box plots show OMPL's own run "
        "attributes.");
  }
  data["paths"] = pathsJson(campaign, runs, options, data);
  return data;
}

}  // namespace arcplan::report
