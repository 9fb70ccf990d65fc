// The VAMP side-by-side program (perf/peer_vamp_mbm) on one problem of each MBM UR5 family: it runs,
// its JSON has the documented structure, and every path it reports goes from the request's start to
// its goal — read here from the request files with yaml-cpp, not through arcplan's MoveIt reader.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using Joints = std::array<double, 6>;

const std::array<std::string, 6> kArmJoints = {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                               "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};

fs::path problemsFolder() {
  const char* shared = std::getenv("ARCPLAN_SHARED_DATA");
  return fs::path(shared != nullptr ? shared : ARCPLAN_SHARED_DATA_DIR) / "mbm_ur5" / "problems";
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("peer_vamp_mbm_test_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

int run(const std::string& arguments, const fs::path& log) {
  const std::string command =
      std::string("'") + PEER_VAMP_MBM_EXECUTABLE + "' " + arguments + " > '" + log.string() + "' 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Start and goal of a MotionPlanRequest YAML, in the arm's joint order.
std::pair<Joints, Joints> requestEnds(const fs::path& file) {
  const YAML::Node request = YAML::LoadFile(file.string());
  std::map<std::string, double> start, goal;
  const YAML::Node state = request["start_state"]["joint_state"];
  for (std::size_t i = 0; i < state["name"].size(); ++i) {
    start[state["name"][i].as<std::string>()] = state["position"][i].as<double>();
  }
  for (const YAML::Node& constraint : request["goal_constraints"][0]["joint_constraints"]) {
    goal[constraint["joint_name"].as<std::string>()] = constraint["position"].as<double>();
  }
  std::pair<Joints, Joints> ends;
  for (std::size_t j = 0; j < kArmJoints.size(); ++j) {
    ends.first[j] = start.at(kArmJoints[j]);
    ends.second[j] = goal.at(kArmJoints[j]);
  }
  return ends;
}

class PeerVampMbm : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(fs::is_directory(problemsFolder())) << problemsFolder();
    const fs::path dir = scratch("run");
    const int code = run("--problems '" + problemsFolder().string() + "' --per-family 1 --time 0.5 --json '" +
                             (dir / "result.json").string() + "'",
                         dir / "log.txt");
    std::ifstream log(dir / "log.txt");
    ASSERT_EQ(code, 0) << std::string(std::istreambuf_iterator<char>(log), {});
    std::ifstream in(dir / "result.json");
    document = nlohmann::json::parse(in);
  }
  static nlohmann::json document;
};
nlohmann::json PeerVampMbm::document;

TEST_F(PeerVampMbm, SummarisesEachPlannerOverAllProblemsAndPerFamily) {
  ASSERT_TRUE(document.contains("planners"));
  ASSERT_EQ(document["planners"].size(), 3u);
  for (const std::string name : {"vamp-rrtc", "RRTConnect", "arc"}) {
    SCOPED_TRACE(name);
    const nlohmann::json& planner = document["planners"].at(name);
    EXPECT_EQ(planner.at("problems").get<int>(), 5);
    const int solved = planner.at("solved").get<int>();
    EXPECT_LE(solved, planner.at("valid_inputs").get<int>());
    EXPECT_LE(planner.at("paths_valid_exact").get<int>(), solved);
    if (solved > 0) {
      EXPECT_LE(planner.at("total_us_median").get<double>(), planner.at("total_us_p95").get<double>());
      EXPECT_GT(planner.at("total_us_median").get<double>(), 0.0);
    } else {
      EXPECT_TRUE(planner.at("total_us_median").is_null());
    }
    ASSERT_EQ(planner.at("families").size(), 5u);
    int familySolved = 0;
    for (const auto& [family, summary] : planner.at("families").items()) {
      EXPECT_EQ(summary.at("problems").get<int>(), 1) << family;
      familySolved += summary.at("solved").get<int>();
    }
    EXPECT_EQ(familySolved, solved);
    EXPECT_EQ(planner.at("per_problem").size(), 5u);
  }
  // VAMP solves every problem its spheres accept (its published MBM result); these five are such.
  EXPECT_EQ(document["planners"]["vamp-rrtc"]["solved"].get<int>(), 5);
  // arcplan plans with the same exact model it is checked with: none of its paths may fail.
  for (const std::string name : {"RRTConnect", "arc"}) {
    EXPECT_EQ(document["planners"][name]["paths_valid_exact"], document["planners"][name]["solved"]) << name;
  }
}

// The certificate's cost is reported for exactly the paths valid under the exact meshes, and the planner's median is
// the median of those (recomputed here from the per-problem values; an odd or even count, numpy's rule).
TEST_F(PeerVampMbm, ReportsWhatCertifyingEachValidPathCost) {
  for (const auto& [name, planner] : document.at("planners").items()) {
    std::vector<double> costs;
    for (const auto& outcome : planner.at("per_problem")) {
      const bool valid = outcome.value("path_valid_exact", false);
      EXPECT_EQ(outcome.contains("certification_us"), valid) << name << " " << outcome.at("problem");
      if (!valid) continue;
      const double us = outcome.at("certification_us").get<double>();
      EXPECT_GT(us, 0.0) << name;  // a valid path has at least one certified motion
      costs.push_back(us);
    }
    if (costs.empty()) {
      EXPECT_TRUE(planner.at("certification_us_median").is_null()) << name;
      continue;
    }
    std::sort(costs.begin(), costs.end());
    const std::size_t n = costs.size();
    const double median = n % 2 == 1 ? costs[n / 2] : 0.5 * (costs[n / 2 - 1] + costs[n / 2]);
    EXPECT_NEAR(planner.at("certification_us_median").get<double>(), median, 1e-9 * median) << name;
    EXPECT_LE(planner.at("certification_us_p95").get<double>(), costs.back()) << name;
    EXPECT_GE(planner.at("certification_us_p95").get<double>(), median) << name;
  }
}

TEST_F(PeerVampMbm, EveryPathGoesFromTheRequestsStartToItsGoal) {
  int paths = 0;
  for (const auto& [name, planner] : document.at("planners").items()) {
    for (const nlohmann::json& entry : planner.at("per_problem")) {
      if (!entry.at("solved").get<bool>()) continue;
      const std::string family = entry.at("family").get<std::string>();
      const std::string problem = entry.at("problem").get<std::string>();
      SCOPED_TRACE(name + " " + family + " " + problem);
      // Problems are named "<family folder>-NNNN".
      const std::string number = problem.substr(problem.rfind('-') + 1);
      const auto [start, goal] = requestEnds(problemsFolder() / family / ("request" + number + ".yaml"));
      const auto first = entry.at("path_start").get<Joints>();
      const auto last = entry.at("path_end").get<Joints>();
      // VAMP keeps configurations in float32: 3.14 rad is off by up to 1.3e-7.
      for (std::size_t j = 0; j < 6; ++j) {
        EXPECT_NEAR(first[j], start[j], 1e-6);
        EXPECT_NEAR(last[j], goal[j], 1e-6);
      }
      ++paths;
    }
  }
  EXPECT_GE(paths, 3);
}

TEST_F(PeerVampMbm, VampsCompiledRobotIsTheUrdfArcplanLoads) {
  // Forward kinematics of robotiq_85_base_link by VAMP (float32) and by arcplan at every start and goal.
  EXPECT_LT(document.at("robot_check").at("max_position_difference_m").get<double>(), 1e-5);
  EXPECT_LT(document.at("robot_check").at("max_rotation_difference_rad").get<double>(), 1e-5);
}

TEST(PeerVampMbmCommandLine, MissingJsonIsAUsageErrorAndWritesNothing) {
  const fs::path dir = scratch("usage");
  EXPECT_EQ(run("--problems '" + problemsFolder().string() + "'", dir / "log.txt"), 2);
  EXPECT_EQ(
      run("--problems '" + (dir / "absent").string() + "' --json '" + (dir / "r.json").string() + "'", dir / "log.txt"),
      2);
  EXPECT_FALSE(fs::exists(dir / "r.json"));
}

}  // namespace
