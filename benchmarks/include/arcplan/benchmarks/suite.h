#pragma once
// A benchmark suite (benchmarks/suites/*.yaml): the problems, the planner configurations and how
// every planner is run on every problem (runs, time limit, TCP speed limit for the scaling).
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "arcplan/collision/scene.h"

namespace arcplan::benchmarks {

// One planner as it appears in the logs and the ranking: a registry planner with fixed parameters.
struct PlannerConfiguration {
  std::string label;                              // unique in the suite; the planner name in the logs ("arc-h0.75r")
  std::string planner;                            // planner registry name ("arc", "RRTConnect")
  std::map<std::string, std::string> parameters;  // OMPL declared parameters, set by name
};

// One planning problem: a scene and the query to solve in it.
struct Problem {
  std::string name;    // unique in the suite, [A-Za-z0-9_-]
  std::string kind;    // "scene file", or the generator's family ("line-sphere", "pillar", "shelf", ...)
  std::string origin;  // where it came from: the scene file, or "generator seed S problem I"
  collision::Scene scene;
  std::string query;  // query name in `scene`
};

// A problem that was loaded but is not planned: its start or goal is invalid (moveit_problems.h).
struct ExcludedProblem {
  std::string name, family;
  std::string start, goal;            // why that end is invalid; empty when it is valid
  std::vector<std::string> contacts;  // "start: link–object" per pair in contact
};

// Seeded random problems around the UR10e on its table (generated_problems.h).
struct GeneratorSettings {
  std::uint64_t seed = 1;
  int lineObstacles = 40;  // one sphere/box/cylinder on or near the straight TCP line
  int pillars = 5;         // a floor-to-ceiling pillar on the line: no arc detour clears it
  int shelves = 5;         // a shelf unit between start and goal: the tool must go over or around it
  int clutter = 0;         // 2-5 small bodies along and around the line
  int armBlocked = 0;      // a body above the line: the tool passes under it, the arm does not
  int walls = 0;           // a thin wall across the line, to pass over
  int nearEndpoint = 0;    // a small body 8-15 cm from the tool at the start or goal
  int tallPillars = 0;     // 2 m pillars, 8-14 cm in radius
  int deepShelves = 0;     // shelves 0.38-0.45 m deep (the usual ones: 0.25-0.35)
  // The straight TCP line keeps 1 cm from every body, the arm following it does not:
  int forearmBeams = 0;  // a beam across the elbow/forearm's sweep
  int lintelGates = 0;   // a gate whose lintel the forearm or wrist meets
  int tiltedTools = 0;   // the tool 30-70 degrees off vertical, a body where the wrist passes
};

// Largest iteration budget of a suite or --budget (OMPL's IterationTerminationCondition counts in
// an unsigned int; more iterations than this would not end within any sensible safety time cap).
constexpr unsigned kMaximumIterationBudget = 1000000000;
// Runs per (problem, planner) a suite (and a baseline) may ask for.
constexpr long long kMaximumRuns = 100000;

struct Suite {
  std::string name;  // [A-Za-z0-9_-]
  std::string description;
  std::filesystem::path sourceFile;
  unsigned runs = 10;
  double timeLimit = 1.0;  // s per run; with an iteration budget only a safety cap
  // Iterations per run (times the planner asks OMPL's termination condition whether to stop, as
  // ompl::base::IterationTerminationCondition counts them): a run ends after this many whatever the
  // machine's load, so single-threaded planners give the same runs everywhere (docs/reproducibility.md).
  std::optional<unsigned> iterationBudget;
  double vMax = 0.25;  // TCP speed limit of the time scaling, m/s
  // m every planner's states and motions keep from obstacles, the robot's own links at most 1 mm of it
  // (collision::requiredDistance; the validity checker and motion validator of every job); a run whose executed
  // path comes closer is not a success.
  double clearance = 0.01;
  std::vector<Problem> problems;
  std::vector<PlannerConfiguration> planners;
  std::optional<GeneratorSettings> generator;     // set when some problems are generated
  std::vector<ExcludedProblem> excludedProblems;  // loaded, start or goal invalid: reported, never planned
  std::vector<std::string> plotProblems;          // problems that get TCP speed-profile and 3D path plots

  const Problem& problem(const std::string& name) const;  // throws arcplan::Error listing the names
};

// Reads a suite file. Scene paths are relative to the suite file's folder or to the data folder.
// Throws arcplan::Error naming file, line and field: unknown keys, missing fields, duplicate or
// malformed names, non-positive runs/time/v_max, unknown plot problems, bad scene files.
Suite loadSuite(const std::filesystem::path& file);

// "thesis" -> the built-in suite file (suiteDirectory()/thesis.yaml); an existing path as given.
// Throws arcplan::Error listing the built-in suites when neither exists.
std::filesystem::path findSuite(const std::string& nameOrFile);

// $ARCPLAN_SUITE_DIR, else the installed share/arcplan/suites, else the source tree's benchmarks/suites.
std::filesystem::path suiteDirectory();

// Restricts `suite` to the named planner labels, in the given order. A label the suite does not
// configure is taken as a registry planner with its default parameters (checked when the campaign starts).
void selectPlanners(Suite& suite, const std::vector<std::string>& labels);

// Settings put over a suite's own by the command line or a Python call; unset ones keep the suite's.
struct SuiteOverrides {
  std::optional<long long> runs;
  std::optional<double> timeLimit;  // s per run
  std::optional<long long> budget;  // iterations per run
  std::optional<double> vMax;       // m/s
};
// Throws arcplan::Error naming the option (--runs, --time, --budget, --vmax) and the range it expects for a
// value out of range, before anything changes.
void applyOverrides(Suite& suite, const SuiteOverrides& overrides);

// True for names usable in file names, OMPL experiment names and SQL values: [A-Za-z0-9_.+-]+.
bool isPlainName(const std::string& name);

}  // namespace arcplan::benchmarks
