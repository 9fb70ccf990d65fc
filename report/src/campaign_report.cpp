#include "arcplan/report/campaign_report.h"

#include <algorithm>
#include <cmath>

#include "arcplan/benchmarks/benchmark_database.h"
#include "arcplan/benchmarks/median_run.h"
#include "arcplan/benchmarks/ranking.h"
#include "arcplan/common/error.h"
#include "arcplan/report/robot_animation.h"
#include "arcplan/robot/robot_model.h"
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

nlohmann::json medianRunJson(const benchmarks::MedianRun& run, const robot::RobotModel& robot,
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
      run.joints.empty() ? nlohmann::json(nullptr) : linkPoseFrames(robot, run.time, run.joints, options.animationRate);
  return entry;
}

// Speed profiles, TCP paths and arm frames of every problem with a paths/ folder.
nlohmann::json pathsJson(const std::filesystem::path& campaign, const benchmarks::BenchmarkDatabase& runs,
                         const CampaignReportOptions& options, nlohmann::json& missing, bool& anyFrames) {
  nlohmann::json paths = nlohmann::json::object();
  const auto& robot = robot::ur10e();
  std::vector<std::string> withoutJoints;
  for (const auto& [problem, planners] : runs.runs) {
    const auto folder = campaign / "paths" / problem;
    if (!std::filesystem::exists(folder / "scene.json")) continue;
    nlohmann::json entry{{"scene", detail::readJsonFile(folder / "scene.json")}, {"planners", nlohmann::json::array()}};
    for (const auto& [planner, plannerRuns] : planners) {
      const auto file = folder / (planner + ".csv");
      if (!std::filesystem::exists(file)) continue;  // no successful run: nothing to draw
      const auto run = benchmarks::readMedianRun(file);
      if (run.joints.empty()) withoutJoints.push_back(file.string());
      auto runJson = medianRunJson(run, robot, options);
      anyFrames = anyFrames || !runJson["frames"].is_null();
      entry["planners"].push_back(std::move(runJson));
    }
    paths[problem] = std::move(entry);
  }
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
  bool anyFrames = false;
  data["paths"] = pathsJson(campaign, runs, options, missing, anyFrames);
  data["robot"] = anyFrames
                      ? nlohmann::json{{"name", robot::ur10e().name()}, {"meshes", robotMeshesJson(robot::ur10e())}}
                      : nlohmann::json(nullptr);
  return data;
}

}  // namespace arcplan::report
