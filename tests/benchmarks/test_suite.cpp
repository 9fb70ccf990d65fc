// Suite files, the built-in suites, and how jobs are split into shards.
#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "arcplan/benchmarks/campaign.h"
#include "arcplan/benchmarks/suite.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "support/command.h"
#include "support/error_message.h"

namespace arcplan::benchmarks {
namespace {

using arcplan::testing::errorMessageOf;

// A suite file in a fresh folder, with the thesis scene copied next to it.
std::filesystem::path writeSuite(const std::string& name, const std::string& text) {
  const auto dir = testing::freshTempDirectory("suite_" + name);
  writeFileAtomically(dir / "scene.yaml",
                      testing::readFile(std::string(ARCPLAN_TEST_DATA_DIR) + "/scenes/thesis_obstacle.yaml"));
  writeFileAtomically(dir / (name + ".yaml"), text);
  return dir / (name + ".yaml");
}

const std::vector<std::string> kRequiredOmplPlanners{"RRT",     "RRTConnect", "RRTstar", "PRM",
                                                     "LazyPRM", "BKPIECE1",   "BiTRRT"};

void expectRequiredPlanners(const Suite& suite) {
  std::set<std::string> labels;
  for (const auto& planner : suite.planners) labels.insert(planner.label);
  for (const auto& name : kRequiredOmplPlanners) EXPECT_EQ(labels.count(name), 1u) << name;
  // The thesis' sagittas as fractions of the half chord, and the automatic search.
  std::map<std::string, const PlannerConfiguration*> arc;
  for (const auto& planner : suite.planners) {
    if (planner.planner == "arc") arc[planner.label] = &planner;
  }
  ASSERT_EQ(arc.size(), 4u);
  for (const auto& [label, fraction] : {std::pair{"arc-h1.00r", 1.0}, {"arc-h0.75r", 0.75}, {"arc-h0.50r", 0.5}}) {
    ASSERT_EQ(arc.count(label), 1u) << label;
    const auto& parameters = arc.at(label)->parameters;
    EXPECT_NEAR(std::stod(parameters.at("sagitta")), fraction * std::stod(parameters.at("half_chord")), 1e-12) << label;
  }
  ASSERT_EQ(arc.count("arc-auto"), 1u);
  EXPECT_EQ(arc.at("arc-auto")->parameters.at("auto"), "1");
}

TEST(Suite, ThesisSuiteHasBothThesisCasesAndEveryRequiredPlanner) {
  const auto suite = loadSuite(findSuite("thesis"));
  EXPECT_EQ(suite.name, "thesis");
  ASSERT_EQ(suite.problems.size(), 2u);
  EXPECT_EQ(suite.problem("straight").scene.obstacles.size(), 1u);  // the table only: case (a)
  ASSERT_EQ(suite.problem("obstacle").scene.obstacles.size(), 2u);
  EXPECT_NEAR(suite.problem("obstacle").scene.obstacles[1].radius, 0.01, 1e-12);  // the particle
  EXPECT_DOUBLE_EQ(suite.vMax, 0.25);
  EXPECT_EQ(suite.plotProblems, (std::vector<std::string>{"straight", "obstacle"}));
  expectRequiredPlanners(suite);
}

TEST(Suite, GeneratedSuiteHasTheProblemsOfEveryFamilyItsFileAsksFor) {
  const auto suite = loadSuite(findSuite("generated"));
  ASSERT_TRUE(suite.generator.has_value());
  EXPECT_DOUBLE_EQ(suite.clearance, 0.01);
  std::map<std::string, int> kinds;
  for (const auto& problem : suite.problems) ++kinds[problem.kind];
  // generated.yaml's counts; its 40 line problems take the shapes sphere, box, cylinder in turn.
  const std::map<std::string, int> expected{
      {"line-sphere", 14}, {"line-box", 13},     {"line-cylinder", 13}, {"pillar", 5},      {"shelf", 5},
      {"clutter", 8},      {"arm-blocked", 6},   {"wall", 6},           {"near-end", 6},    {"pillar-tall", 4},
      {"shelf-deep", 3},   {"forearm-beam", 12}, {"lintel-gate", 12},   {"tilted-tool", 12}};
  EXPECT_EQ(kinds, expected);
  int total = 0;
  for (const auto& [kind, count] : expected) total += count;
  EXPECT_EQ(total, 119);
  EXPECT_EQ(suite.problems.size(), 119u);
  expectRequiredPlanners(suite);
}

TEST(Suite, FindSuiteNamesTheBuiltInSuitesWhenNothingMatches) {
  const auto message = errorMessageOf([] { findSuite("no_such_suite"); });
  EXPECT_NE(message.find("no_such_suite"), std::string::npos) << message;
  EXPECT_NE(message.find("thesis"), std::string::npos) << message;
  EXPECT_NE(message.find("generated"), std::string::npos) << message;
}

TEST(Suite, AFolderNamedLikeABuiltInSuiteIsNotTakenForASuiteFile) {
  const auto dir = testing::freshTempDirectory("suite_cwd");
  std::filesystem::create_directories(dir / "thesis");  // e.g. a campaign's --out folder
  const auto previous = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  const auto found = findSuite("thesis");
  std::filesystem::current_path(previous);
  EXPECT_EQ(found, suiteDirectory() / "thesis.yaml");
  EXPECT_NE(errorMessageOf([&] { loadSuite(dir / "thesis"); }).find("not a file"), std::string::npos);
}

TEST(Suite, ReadsProblemsPlannersAndDefaults) {
  const auto file = writeSuite("small", R"(name: small
runs: 3
time_limit: 0.25
problems:
  - {name: particle, scene: scene.yaml}
planners:
  - RRTConnect
  - {name: arc-thesis, planner: arc, params: {sagitta: 0.1, half_chord: 0.2}}
)");
  const auto suite = loadSuite(file);
  EXPECT_EQ(suite.runs, 3u);
  EXPECT_DOUBLE_EQ(suite.timeLimit, 0.25);
  EXPECT_DOUBLE_EQ(suite.vMax, 0.25);       // default
  EXPECT_DOUBLE_EQ(suite.clearance, 0.01);  // default
  ASSERT_EQ(suite.problems.size(), 1u);
  EXPECT_EQ(suite.problems[0].query, "A_to_B");  // the scene's first query
  ASSERT_EQ(suite.planners.size(), 2u);
  EXPECT_EQ(suite.planners[0].label, "RRTConnect");
  EXPECT_EQ(suite.planners[0].planner, "RRTConnect");
  EXPECT_EQ(suite.planners[1].planner, "arc");
  EXPECT_EQ(suite.planners[1].parameters.at("half_chord"), "0.2");
}

struct BadSuite {
  std::string name;
  std::string text;
  std::vector<std::string> expected;  // fragments of the message
};

TEST(Suite, BadSuiteFilesAreReportedWithFileLineAndField) {
  const std::vector<BadSuite> cases{
      {"unknown_key",
       "name: x\nrun: 3\nproblems: [{name: p, scene: scene.yaml}]\nplanners: [RRT]\n",
       {"unknown_key.yaml:2", "unknown key 'run'"}},
      {"no_planners", "name: x\nproblems: [{name: p, scene: scene.yaml}]\n", {"no_planners.yaml", "'planners'"}},
      {"no_problems", "name: x\nplanners: [RRT]\n", {"no_problems.yaml", "no problems"}},
      {"bad_runs",
       "name: x\nruns: 0\nproblems: [{name: p, scene: scene.yaml}]\nplanners: [RRT]\n",
       {"bad_runs.yaml:2", "suite.runs: must be between 1 and 100000"}},
      {"bad_time",
       "name: x\ntime_limit: -1\nproblems: [{name: p, scene: scene.yaml}]\nplanners: [RRT]\n",
       {"bad_time.yaml:2", "suite.time_limit: expected a positive number"}},
      {"bad_name",
       "name: x\nproblems: [{name: 'a b', scene: scene.yaml}]\nplanners: [RRT]\n",
       {"bad_name.yaml:2", "'a b'", "plain name"}},
      {"duplicate_planner",
       "name: x\nproblems: [{name: p, scene: scene.yaml}]\nplanners: [RRT, RRT]\n",
       {"duplicate_planner.yaml:3", "duplicate planner name 'RRT'"}},
      {"missing_scene",
       "name: x\nproblems: [{name: p, scene: nowhere.yaml}]\nplanners: [RRT]\n",
       {"missing_scene.yaml:2", "nowhere.yaml", "not found"}},
      {"unknown_query",
       "name: x\nproblems: [{name: p, scene: scene.yaml, query: C_to_D}]\nplanners: [RRT]\n",
       {"unknown_query.yaml:2", "C_to_D", "A_to_B"}},
      {"unknown_plot",
       "name: x\nproblems: [{name: p, scene: scene.yaml}]\nplanners: [RRT]\nplots: [q]\n",
       {"unknown_plot.yaml:4", "no problem named 'q'"}},
      {"not_yaml", "name: [x\n", {"not_yaml.yaml", "malformed YAML"}},
      {"no_seed", "name: x\ngenerate: {pillars: 1}\nplanners: [RRT]\n", {"no_seed.yaml:2", "missing 'seed'"}},
      {"bad_clearance",
       "name: x\nclearance: -0.01\nproblems: [{name: p, scene: scene.yaml}]\nplanners: [RRT]\n",
       {"bad_clearance.yaml:2", "suite.clearance: must be in [0, 1) m"}},
      {"bad_family",
       "name: x\ngenerate: {seed: 1, walls: -1}\nplanners: [RRT]\n",
       {"bad_family.yaml:2", "generate.walls: must be between 0 and 1000"}},
  };
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.name);
    const auto file = writeSuite(bad.name, bad.text);
    const auto message = errorMessageOf([&] { loadSuite(file); });
    for (const auto& fragment : bad.expected) EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

TEST(Suite, SelectPlannersKeepsTheGivenOrderAndAddsRegistryPlanners) {
  auto suite = loadSuite(findSuite("thesis"));
  selectPlanners(suite, {"RRTConnect", "arc-h0.50r", "PRMstar"});
  ASSERT_EQ(suite.planners.size(), 3u);
  EXPECT_EQ(suite.planners[0].label, "RRTConnect");
  EXPECT_EQ(suite.planners[1].label, "arc-h0.50r");
  EXPECT_EQ(suite.planners[1].parameters.at("sagitta"), "0.1");
  EXPECT_EQ(suite.planners[2].planner, "PRMstar");
  EXPECT_TRUE(suite.planners[2].parameters.empty());
  EXPECT_NE(errorMessageOf([&] { selectPlanners(suite, {"a/b"}); }).find("'a/b'"), std::string::npos);
}

TEST(Shards, ParseAcceptsOnlyKOfN) {
  EXPECT_EQ(parseShard("2/8").index, 2);
  EXPECT_EQ(parseShard("2/8").count, 8);
  EXPECT_EQ(parseShard("1/1").count, 1);
  for (const char* bad : {"0/2", "3/2", "2", "a/b", "1.5/2", "-1/2", "1/0", ""}) {
    const auto message = errorMessageOf([&] { parseShard(bad); });
    EXPECT_NE(message.find("--shard"), std::string::npos) << bad << ": " << message;
  }
}

TEST(Shards, SharesPartitionTheJobsEvenly) {
  Suite suite;
  suite.problems.resize(7);
  suite.planners.resize(5);
  const auto all = campaignJobs(suite);
  ASSERT_EQ(all.size(), 35u);
  for (int count : {1, 2, 3, 8, 40}) {
    std::vector<int> seen(all.size(), 0);
    std::size_t smallest = all.size(), largest = 0;
    for (int index = 1; index <= count; ++index) {
      const auto share = shardJobs(all, {index, count});
      smallest = std::min(smallest, share.size());
      largest = std::max(largest, share.size());
      for (const auto& job : share) {
        const auto position = std::find(all.begin(), all.end(), job) - all.begin();
        ++seen[static_cast<std::size_t>(position)];
      }
      EXPECT_EQ(share, shardJobs(all, {index, count}));  // deterministic
    }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; })) << count << " shards";
    EXPECT_LE(largest - smallest, 1u) << count << " shards";
  }
}

}  // namespace
}  // namespace arcplan::benchmarks
