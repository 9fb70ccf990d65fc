#include "arcplan/benchmarks/suite.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <set>

#include "arcplan/benchmarks/generated_problems.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/common/yaml_reading.h"
#include "moveit_suite_entry.h"

namespace arcplan::benchmarks {
namespace {

// Bounds that keep a typo from starting a campaign of months or generating problems for hours.
constexpr long long kMaximumGeneratedPerKind = 1000;

// Reading context for messages: "suites/x.yaml:12:3: runs: must be between 1 and 100000".
struct SuiteReader {
  YamlReader yaml;

  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const {
    throw Error(yaml.position(node) + ": " + message);
  }

  // The value of `key` in `map` ("what" names the map in messages, e.g. "problem").
  YAML::Node field(const YAML::Node& map, const std::string& key, const std::string& what) const {
    return yaml.required(map, key.c_str(), what);
  }

  std::string text(const YAML::Node& map, const std::string& key, const std::string& what) const {
    return yaml.text(field(map, key, what), what + "." + key);
  }

  std::string name(const YAML::Node& map, const std::string& key, const std::string& what) const {
    auto value = text(map, key, what);
    if (!isPlainName(value)) {
      yaml.fail(map[key], what + "." + key,
                "'" + value + "' is not a plain name of letters, digits and _ . + - (it names files and log entries)");
    }
    return value;
  }

  double positive(const YAML::Node& map, const std::string& key, const std::string& what) const {
    return yaml.positive(field(map, key, what), what + "." + key);
  }

  // A length in metres, >= 0 and below a metre (more would leave no room to move).
  double distance(const YAML::Node& map, const std::string& key, const std::string& what) const {
    const auto node = field(map, key, what);
    const double value = yaml.number(node, what + "." + key);
    if (value < 0.0 || value >= 1.0) yaml.fail(node, what + "." + key, "must be in [0, 1) m");
    return value;
  }

  long long count(const YAML::Node& map, const std::string& key, const std::string& what, long long minimum,
                  long long maximum) const {
    return yaml.wholeNumber(field(map, key, what), what + "." + key, minimum, maximum);
  }

  std::filesystem::path scenePath(const YAML::Node& problem) const {
    const std::filesystem::path given = text(problem, "scene", "problem");
    if (given.is_absolute()) return given;
    const auto besideSuite = yaml.file().parent_path() / given;
    if (std::filesystem::exists(besideSuite)) return besideSuite;
    const auto inData = resolveDataPath(given);
    if (std::filesystem::exists(inData)) return inData;
    fail(problem["scene"], "scene file '" + given.string() + "' not found (looked next to the suite and in " +
                               dataDirectory().string() + ")");
  }

  Problem problemFromFile(const YAML::Node& node) const {
    yaml.checkKeys(node, "problem", {"name", "scene", "query"});
    Problem problem;
    problem.name = name(node, "name", "problem");
    problem.kind = "scene file";
    const auto path = scenePath(node);
    problem.origin = path.string();
    try {
      problem.scene = collision::loadScene(path);
    } catch (const Error& e) {
      fail(node, "problem '" + problem.name + "': " + e.what());
    }
    const std::string query = node["query"] ? text(node, "query", "problem") : std::string();
    try {
      problem.query = problem.scene.query(query).name;
    } catch (const Error& e) {
      fail(node, "problem '" + problem.name + "': " + e.what());
    }
    return problem;
  }

  PlannerConfiguration planner(const YAML::Node& node) const {
    PlannerConfiguration configuration;
    if (node.IsScalar()) {  // "- RRTConnect": the planner with its defaults, labelled by its name
      configuration.label = yaml.text(node, "planner");
      configuration.planner = configuration.label;
      if (!isPlainName(configuration.label))
        fail(node, "planner name '" + configuration.label + "' is not a plain name");
      return configuration;
    }
    yaml.checkKeys(node, "planner", {"name", "planner", "params"});
    configuration.label = name(node, "name", "planner");
    configuration.planner = node["planner"] ? text(node, "planner", "planner") : configuration.label;
    if (const auto params = node["params"]) {
      const std::string field = "planner '" + configuration.label + "'.params";
      yaml.expectMap(params, field);
      for (const auto& entry : params) {
        const auto key = yaml.text(entry.first, field);
        configuration.parameters[key] = yaml.text(entry.second, field + "." + key);
      }
    }
    return configuration;
  }

  GeneratorSettings generator(const YAML::Node& node) const {
    GeneratorSettings settings;
    const std::vector<std::pair<const char*, int*>> counts = {
        {"line_obstacles", &settings.lineObstacles},
        {"pillars", &settings.pillars},
        {"shelves", &settings.shelves},
        {"clutter", &settings.clutter},
        {"arm_blocked", &settings.armBlocked},
        {"walls", &settings.walls},
        {"near_endpoint", &settings.nearEndpoint},
        {"tall_pillars", &settings.tallPillars},
        {"deep_shelves", &settings.deepShelves},
        {"forearm_beams", &settings.forearmBeams},
        {"lintel_gates", &settings.lintelGates},
        {"tilted_tools", &settings.tiltedTools},
    };
    std::vector<std::string> keys{"seed"};
    for (const auto& [key, field] : counts) keys.emplace_back(key);
    yaml.checkKeys(node, "generate", keys);
    if (!node["seed"]) fail(node, "generate: missing 'seed' (problems must be reproducible)");
    settings.seed =
        static_cast<std::uint64_t>(count(node, "seed", "generate", 0, std::numeric_limits<long long>::max()));
    for (const auto& [key, field] : counts) {
      if (node[key]) *field = static_cast<int>(count(node, key, "generate", 0, kMaximumGeneratedPerKind));
    }
    return settings;
  }
};

}  // namespace

bool isPlainName(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.' || c == '+' || c == '-';
  });
}

const Problem& Suite::problem(const std::string& wanted) const {
  for (const auto& candidate : problems) {
    if (candidate.name == wanted) return candidate;
  }
  std::string list;
  for (const auto& candidate : problems) list += (list.empty() ? "" : ", ") + candidate.name;
  throw Error("suite '" + name + "' has no problem '" + wanted + "' (problems: " + list + ")");
}

namespace {

Suite readSuite(const SuiteReader& reader, const YAML::Node& root) {
  if (!root || !root.IsMap())
    throw Error(reader.yaml.file().string() + ": a suite must be a YAML map (name, runs, problems, planners)");
  reader.yaml.checkKeys(root, "suite",
                        {"name", "description", "runs", "time_limit", "budget", "v_max", "clearance", "problems",
                         "generate", "moveit_problems", "planners", "plots"});

  Suite suite;
  suite.sourceFile = reader.yaml.file();
  suite.name = reader.name(root, "name", "suite");
  if (root["description"]) suite.description = reader.text(root, "description", "suite");
  if (root["runs"]) suite.runs = static_cast<unsigned>(reader.count(root, "runs", "suite", 1, kMaximumRuns));
  if (root["time_limit"]) suite.timeLimit = reader.positive(root, "time_limit", "suite");
  if (root["budget"]) {
    suite.iterationBudget = static_cast<unsigned>(reader.count(root, "budget", "suite", 1, kMaximumIterationBudget));
  }
  if (root["v_max"]) suite.vMax = reader.positive(root, "v_max", "suite");
  if (root["clearance"]) suite.clearance = reader.distance(root, "clearance", "suite");

  if (const auto problems = root["problems"]) {
    if (!problems.IsSequence()) reader.fail(problems, "problems must be a list");
    for (const auto& node : problems) suite.problems.push_back(reader.problemFromFile(node));
  }
  if (const auto generate = root["generate"]) {
    suite.generator = reader.generator(generate);
    for (auto& problem : generateProblems(*suite.generator)) suite.problems.push_back(std::move(problem));
  }
  if (const auto moveit = root["moveit_problems"]) detail::addMoveItSuiteEntry(reader.yaml, moveit, suite);
  if (suite.problems.empty())
    reader.fail(root, "suite '" + suite.name + "' has no problems (give 'problems', 'generate' or 'moveit_problems')");
  std::set<std::string> problemNames;
  for (const auto& problem : suite.problems) {
    if (!problemNames.insert(problem.name).second)
      reader.fail(root["problems"], "duplicate problem name '" + problem.name + "'");
  }

  const auto planners = root["planners"];
  if (!planners || !planners.IsSequence() || planners.size() == 0) {
    reader.fail(planners ? planners : root, "suite '" + suite.name + "': 'planners' must be a non-empty list");
  }
  std::set<std::string> labels;
  for (const auto& node : planners) {
    auto configuration = reader.planner(node);
    if (!labels.insert(configuration.label).second)
      reader.fail(node, "duplicate planner name '" + configuration.label + "'");
    suite.planners.push_back(std::move(configuration));
  }

  if (const auto plots = root["plots"]) {
    if (!plots.IsSequence()) reader.fail(plots, "plots must be a list of problem names");
    for (const auto& node : plots) {
      const auto problem = reader.yaml.text(node, "plots");
      if (problemNames.count(problem) == 0)
        reader.fail(node, "plots: no problem named '" + problem + "' in this suite");
      suite.plotProblems.push_back(problem);
    }
  }
  return suite;
}

}  // namespace

Suite loadSuite(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file))
    throw Error("suite file " + file.string() + " not found (or not a file)");
  const SuiteReader reader{YamlReader(file)};
  // The reader checks every node's kind before it uses it; a yaml-cpp exception it did not anticipate
  // still becomes an arcplan::Error at its line.
  try {
    return readSuite(reader, reader.yaml.load("suite file"));
  } catch (const YAML::Exception& e) {
    throw Error(reader.yaml.position(e.mark) + ": not a valid suite: " + e.msg);
  }
}

std::filesystem::path suiteDirectory() {
  if (const char* value = std::getenv("ARCPLAN_SUITE_DIR"); value != nullptr && *value != '\0') return value;
  const auto installed = dataDirectory() / "suites";
  if (std::filesystem::exists(installed)) return installed;
  return ARCPLAN_SOURCE_SUITE_DIR;
}

std::filesystem::path findSuite(const std::string& nameOrFile) {
  if (std::filesystem::is_regular_file(nameOrFile)) return nameOrFile;  // (a folder named "thesis" is not a suite)
  if (isPlainName(nameOrFile)) {
    const auto builtIn = suiteDirectory() / (nameOrFile + ".yaml");
    if (std::filesystem::exists(builtIn)) return builtIn;
  }
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(suiteDirectory(), ec)) {
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  std::string list;
  for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
  throw Error("--suite: '" + nameOrFile + "' is neither a suite file nor a built-in suite (built-in: " +
              (list.empty() ? std::string("none found in " + suiteDirectory().string()) : list) + ")");
}

void selectPlanners(Suite& suite, const std::vector<std::string>& labels) {
  std::vector<PlannerConfiguration> selected;
  for (const auto& label : labels) {
    if (std::any_of(selected.begin(), selected.end(), [&](const auto& p) { return p.label == label; })) continue;
    const auto found = std::find_if(suite.planners.begin(), suite.planners.end(),
                                    [&](const PlannerConfiguration& p) { return p.label == label; });
    if (found != suite.planners.end()) {
      selected.push_back(*found);
    } else if (isPlainName(label)) {
      selected.push_back({label, label, {}});  // a registry planner with its defaults
    } else {
      throw Error("--planners: '" + label + "' is not a plain planner name");
    }
  }
  if (selected.empty()) throw Error("--planners: the list is empty");
  suite.planners = std::move(selected);
}

void applyOverrides(Suite& suite, const SuiteOverrides& overrides) {
  const auto& o = overrides;
  if (o.runs && *o.runs < 1) throw Error("--runs must be at least 1");
  if (o.runs && *o.runs > kMaximumRuns) throw Error("--runs must be at most " + std::to_string(kMaximumRuns));
  if (o.timeLimit && (!(*o.timeLimit > 0.0) || !std::isfinite(*o.timeLimit))) {
    throw Error("--time must be a positive number of seconds");
  }
  if (o.budget && (*o.budget < 1 || *o.budget > kMaximumIterationBudget)) {
    throw Error("--budget must be a whole number of iterations from 1 to " + std::to_string(kMaximumIterationBudget));
  }
  if (o.vMax && (!(*o.vMax > 0.0) || !std::isfinite(*o.vMax)))
    throw Error("--vmax must be a positive TCP speed in m/s");
  if (o.runs) suite.runs = static_cast<unsigned>(*o.runs);
  if (o.timeLimit) suite.timeLimit = *o.timeLimit;
  if (o.budget) suite.iterationBudget = static_cast<unsigned>(*o.budget);
  if (o.vMax) suite.vMax = *o.vMax;
}

}  // namespace arcplan::benchmarks
