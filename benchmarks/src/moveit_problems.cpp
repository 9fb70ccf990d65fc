#include "arcplan/benchmarks/moveit_problems.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "arcplan/collision/collision_model.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "moveit_suite_entry.h"
#include "arcplan/planners/planning_problem.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::benchmarks {
namespace {

// The start of Problem::origin for MoveIt problems ("MoveIt <scene file> + <request file>").
const std::string kMoveItOrigin = "MoveIt ";

// NNNN -> (scene, request) of one folder.
std::map<std::string, std::pair<std::filesystem::path, std::filesystem::path>> pairsIn(
    const std::filesystem::path& folder) {
  static const std::regex pattern("(scene|request)([0-9]+)\\.yaml");
  std::map<std::string, std::pair<std::filesystem::path, std::filesystem::path>> pairs;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    std::smatch match;
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file() || !std::regex_match(name, match, pattern)) continue;
    auto& pair = pairs[match[2].str()];
    (match[1].str() == "scene" ? pair.first : pair.second) = entry.path();
  }
  for (const auto& [number, pair] : pairs) {
    if (pair.first.empty()) throw Error(pair.second.string() + ": no scene" + number + ".yaml beside this request");
    if (pair.second.empty()) throw Error(pair.first.string() + ": no request" + number + ".yaml beside this scene");
  }
  return pairs;
}

void addFolder(const std::filesystem::path& folder, const std::string& family, std::vector<MoveItProblemFiles>& out) {
  for (const auto& [number, pair] : pairsIn(folder))
    out.push_back({family, family + "-" + number, pair.first, pair.second});
}

EndpointValidity checkEndpoint(const collision::QueryEndpoint& endpoint, const collision::CollisionModel& model,
                               const robot::UrInverseKinematics& ik, const std::string& label) {
  EndpointValidity validity;
  if (endpoint.joints) {
    collision::CollisionData data(model);
    const auto report = collision::collide(model, data, *endpoint.joints);
    if (!report.valid) {
      validity.valid = false;
      validity.contacts = report.collisions;
      validity.problem = "in collision: " + collision::describeCollisions(report);
      return validity;
    }
  }
  try {  // the joint limits, and for a pose the IK solutions (collision-free ones)
    planners::resolveEndpoint(endpoint, model, ik, label);
  } catch (const Error& e) {
    validity.valid = false;
    validity.problem = e.what();
  }
  return validity;
}

}  // namespace

std::vector<MoveItProblemFiles> listMoveItProblems(const std::filesystem::path& folder) {
  if (!std::filesystem::is_directory(folder)) throw Error("MoveIt problems: folder " + folder.string() + " not found");
  std::vector<MoveItProblemFiles> problems;
  addFolder(folder, folder.filename().string(), problems);
  if (problems.empty()) {  // one family folder deep
    std::vector<std::filesystem::path> families;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
      if (entry.is_directory()) families.push_back(entry.path());
    }
    std::sort(families.begin(), families.end());
    for (const auto& family : families) addFolder(family, family.filename().string(), problems);
  }
  if (problems.empty()) {
    throw Error("MoveIt problems: no sceneNNNN.yaml/requestNNNN.yaml pairs in " + folder.string() +
                " or its subfolders");
  }
  return problems;
}

ProblemValidity checkEndpoints(const collision::Scene& scene, const std::string& queryName) {
  const collision::Query& query = scene.query(queryName);
  const auto model = collision::makeCollisionModel(scene);
  const robot::UrInverseKinematics ik(model->robot());
  return {checkEndpoint(query.start, *model, ik, "start"), checkEndpoint(query.goal, *model, ik, "goal")};
}

void addMoveItProblems(const MoveItProblemSource& source, Suite& suite) {
  for (const auto& files : listMoveItProblems(source.folder)) {
    collision::MoveItProblem loaded = collision::loadMoveItProblem(files.scene, files.request, source.robot);
    Problem problem;
    problem.name = files.name;
    problem.kind = files.family;
    problem.origin = kMoveItOrigin + files.scene.string() + " + " + files.request.filename().string();
    problem.query = loaded.scene.queries.front().name;
    problem.scene = std::move(loaded.scene);
    const ProblemValidity validity = checkEndpoints(problem.scene, problem.query);
    if (validity.valid()) {
      suite.problems.push_back(std::move(problem));
    } else {
      ExcludedProblem excluded{problem.name,
                               problem.kind,
                               validity.start.valid ? "" : validity.start.problem,
                               validity.goal.valid ? "" : validity.goal.problem,
                               {}};
      for (const auto& [end, check] : {std::pair{"start", &validity.start}, std::pair{"goal", &validity.goal}}) {
        for (const auto& [a, b] : check->contacts) excluded.contacts.push_back(std::string(end) + ": " + a + "–" + b);
      }
      suite.excludedProblems.push_back(std::move(excluded));
    }
  }
}

std::string validityTable(const Suite& suite) {
  const auto fromMoveIt = [](const Problem& problem) { return problem.origin.rfind(kMoveItOrigin, 0) == 0; };
  if (suite.excludedProblems.empty() && std::none_of(suite.problems.begin(), suite.problems.end(), fromMoveIt))
    return "";
  struct Counts {
    int valid = 0, invalidStart = 0, invalidGoal = 0;
    std::map<std::string, int> reasons;  // what made them invalid, counted
  };
  std::map<std::string, Counts> families;
  for (const auto& problem : suite.problems) {
    if (fromMoveIt(problem)) ++families[problem.kind].valid;
  }
  for (const auto& excluded : suite.excludedProblems) {
    Counts& counts = families[excluded.family];
    counts.invalidStart += excluded.start.empty() ? 0 : 1;
    counts.invalidGoal += excluded.goal.empty() ? 0 : 1;
    for (const auto& contact : excluded.contacts) ++counts.reasons[contact];
    // Not a contact (joint limits, no IK solution): the message itself.
    if (excluded.contacts.empty())
      ++counts.reasons[excluded.start.empty() ? "goal: " + excluded.goal : "start: " + excluded.start];
  }
  std::ostringstream out;
  out << "| family | problems | valid | invalid start | invalid goal | pairs in contact (problems) "
         "|\n|---|---|---|---|---|---|\n";
  for (const auto& [family, counts] : families) {
    const int total =
        counts.valid + static_cast<int>(std::count_if(suite.excludedProblems.begin(), suite.excludedProblems.end(),
                                                      [&](const ExcludedProblem& e) { return e.family == family; }));
    out << "| " << family << " | " << total << " | " << counts.valid << " | " << counts.invalidStart << " | "
        << counts.invalidGoal << " | ";
    bool first = true;
    for (const auto& [reason, count] : counts.reasons) {
      out << (first ? "" : "; ") << reason << " (" << count << ")";
      first = false;
    }
    out << " |\n";
  }
  return out.str();
}

}  // namespace arcplan::benchmarks

namespace arcplan::benchmarks::detail {
namespace {

std::filesystem::path entryPath(const YamlReader& yaml, const YAML::Node& entry, const char* key, bool required) {
  const YAML::Node node = entry[key];
  if (!node) {
    if (required) yaml.fail(entry, "moveit_problems", std::string("missing '") + key + "'");
    return {};
  }
  const std::filesystem::path given = yaml.text(node, std::string("moveit_problems.") + key);
  if (given.is_absolute()) {
    if (!std::filesystem::exists(given))
      yaml.fail(node, std::string("moveit_problems.") + key, given.string() + " not found");
    return given;
  }
  const auto besideSuite = yaml.file().parent_path() / given;
  if (std::filesystem::exists(besideSuite)) return besideSuite;
  const auto shared = sharedDataDirectory() / given;
  if (std::filesystem::exists(shared)) return shared;
  yaml.fail(node, std::string("moveit_problems.") + key,
            "'" + given.string() + "' not found next to the suite nor in the shared data folder " +
                sharedDataDirectory().string() + " (set ARCPLAN_SHARED_DATA to the folder holding it)");
}

}  // namespace

void addMoveItSuiteEntry(const YamlReader& yaml, const YAML::Node& entry, Suite& suite) {
  yaml.checkKeys(entry, "moveit_problems", {"folder", "urdf", "ur_type", "description", "kinematics", "srdf"});
  if (static_cast<bool>(entry["urdf"]) == static_cast<bool>(entry["ur_type"]))
    yaml.fail(entry, "moveit_problems", "expected either 'urdf' or 'ur_type'");
  MoveItProblemSource source;
  source.folder = entryPath(yaml, entry, "folder", true);
  source.robot.urdf = entryPath(yaml, entry, "urdf", false);
  source.robot.srdf = entryPath(yaml, entry, "srdf", false);
  if (const auto type = entry["ur_type"]) {
    source.robot.urDescription = {yaml.text(type, "moveit_problems.ur_type"),
                                  entryPath(yaml, entry, "description", false),
                                  entryPath(yaml, entry, "kinematics", false)};
  } else if (entry["description"] || entry["kinematics"]) {
    yaml.fail(entry, "moveit_problems", "'description' and 'kinematics' go with 'ur_type'");
  }
  try {
    addMoveItProblems(source, suite);
  } catch (const Error& e) {
    yaml.fail(entry, "moveit_problems", e.what());
  }
}

}  // namespace arcplan::benchmarks::detail
