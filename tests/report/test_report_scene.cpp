// What the campaign report's 3D view gets from a real campaign (`arcplan bench`): every obstacle of a
// MoveIt scene (box, cylinder [height, radius], sphere, mesh; object pose · primitive pose with
// quaternions [x, y, z, w]) and of a scene file (an STL mesh), a body the robot holds, and every link
// of a robot with a gripper beyond the flange. Expected poses and sizes are worked out by hand from the input
// files (tests/report/drawn_campaign).
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/report/campaign_report.h"
#include "arcplan/report/robot_animation.h"
#include "arcplan/robot/robot_model.h"
#include "support/base64_decoding.h"
#include "support/command.h"
#include "support/robot_files.h"

namespace {

using arcplan::testing::decodeBase64Array;
using Json = nlohmann::json;

// The campaign's files (tests/report/drawn_campaign, shared with browser_reports.sh) copied to `dir`, its
// MoveIt problem written by write_drawn_moveit.sh (the one place its text lives), and beside them
// gripper.urdf: arcplan's UR10e with a box body on tool0 and a finger 0.1 m further.
void writeDrawnCampaign(const std::filesystem::path& dir) {
  const std::filesystem::path fixture = ARCPLAN_DRAWN_CAMPAIGN_DIR;
  std::filesystem::copy(fixture, dir, std::filesystem::copy_options::recursive);
  const std::string writer =
      "bash '" + (fixture.parent_path() / "write_drawn_moveit.sh").string() + "' '" + dir.string() + "'";
  ASSERT_EQ(std::system(writer.c_str()), 0) << writer;
  std::string urdf = arcplan::testing::ur10eUrdfText();
  urdf.insert(urdf.rfind("</robot>"), arcplan::testing::readFile(fixture / "gripper_links.xml"));
  std::ofstream(dir / "gripper.urdf") << urdf;
}

class ReportScene : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    const auto dir = arcplan::testing::freshTempDirectory("report_scene");
    writeDrawnCampaign(dir);
    const auto result = arcplan::testing::runArcplan({"bench", "--suite", (dir / "suite.yaml").string(), "--out",
                                                      (dir / "campaign").string(), "--no-plots", "--quiet", "-j", "1"});
    ASSERT_EQ(result.exitCode, 0) << result.err;
    data_ = new Json(arcplan::report::campaignReportData(dir / "campaign", dir / "campaign" / "report.html"));
    campaign_ = new std::filesystem::path(dir / "campaign");
  }
  static void TearDownTestSuite() {
    delete data_;
    delete campaign_;
  }

  static const Json& problem(const std::string& name) {
    for (const auto& [key, value] : data_->at("paths").items()) {
      if (key.size() >= name.size() && key.compare(key.size() - name.size(), name.size(), name) == 0) return value;
    }
    throw std::runtime_error("no plot problem " + name + " in " + data_->at("paths").dump().substr(0, 200));
  }
  static const Json& obstacle(const std::string& problemName, const std::string& id) {
    for (const auto& obstacle : problem(problemName)["scene"]["obstacles"]) {
      if (obstacle["name"].get<std::string>().rfind(id, 0) == 0) return obstacle;
    }
    throw std::runtime_error("no obstacle " + id);
  }
  static void expectPose(const Json& obstacle, const Eigen::Vector3d& position, const Eigen::Matrix3d& rotation) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(obstacle["position"][i].get<double>(), position[i], 1e-9) << obstacle["name"];
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(obstacle["rotation"][i][j].get<double>(), rotation(i, j), 1e-9);
    }
  }
  // One campaign (a few seconds) for all checks: ctest runs every test in its own process.
  static void expectMoveItPrimitives();
  static void expectSceneFileMesh();
  static void expectGripper();
  static Json* data_;
  static std::filesystem::path* campaign_;  // the finished campaign, for the bad-input test
};
Json* ReportScene::data_ = nullptr;
std::filesystem::path* ReportScene::campaign_ = nullptr;

Eigen::Matrix3d rows(std::initializer_list<double> values) {
  Eigen::Matrix3d m;
  auto it = values.begin();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = *it++;
  return m;
}

void ReportScene::expectMoveItPrimitives() {
  const auto& obstacles = problem("moveit-0001")["scene"]["obstacles"];
  EXPECT_EQ(obstacles.size(), 4u);
  // The crate's object is turned 90° about z: its box 0.1 m along the object's x is at +0.1 m in y.
  const auto& crate = obstacle("moveit-0001", "crate");
  EXPECT_EQ(crate["shape"], "box");
  EXPECT_EQ(crate["size"], Json({0.1, 0.2, 0.3}));
  expectPose(crate, {-0.8, 0.3, 0.3}, rows({0, -1, 0, 1, 0, 0, 0, 0, 1}));
  // MoveIt's cylinder is [height, radius]; the primitive turned 90° about x.
  const auto& can = obstacle("moveit-0001", "can");
  EXPECT_EQ(can["shape"], "cylinder");
  EXPECT_DOUBLE_EQ(can["length"].get<double>(), 0.4);
  EXPECT_DOUBLE_EQ(can["radius"].get<double>(), 0.05);
  expectPose(can, {-0.8, -0.3, 0.2}, rows({1, 0, 0, 0, 0, -1, 0, 1, 0}));
  const auto& ball = obstacle("moveit-0001", "ball");
  EXPECT_EQ(ball["shape"], "sphere");
  EXPECT_DOUBLE_EQ(ball["radius"].get<double>(), 0.07);
  expectPose(ball, {-0.6, -0.6, 0.5}, Eigen::Matrix3d::Identity());
  // The mesh: its four vertices in the obstacle frame, four triangles, placed by the mesh pose.
  const auto& wedge = obstacle("moveit-0001", "wedge");
  EXPECT_EQ(wedge["shape"], "mesh");
  EXPECT_EQ(wedge["triangles"], 4);
  EXPECT_EQ(decodeBase64Array<float>(wedge["positions"]),
            std::vector<float>({0, 0, 0, 0.1f, 0, 0, 0, 0.1f, 0, 0, 0, 0.1f}));
  EXPECT_EQ(decodeBase64Array<std::uint32_t>(wedge["indices"]),
            std::vector<std::uint32_t>({0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}));
  expectPose(wedge, {-0.7, 0.6, 0.1}, Eigen::Matrix3d::Identity());
}

void ReportScene::expectSceneFileMesh() {
  const auto& part = obstacle("stl", "part");
  EXPECT_EQ(part["shape"], "mesh");
  EXPECT_EQ(part["triangles"], 4);
  const auto positions = decodeBase64Array<float>(part["positions"]);
  ASSERT_EQ(positions.size() % 3, 0u);
  // Every vertex is one of the tetrahedron's corners scaled 2x: (0,0,0), (0.2,0,0), (0,0.2,0), (0,0,0.2).
  std::set<int> corners;
  for (std::size_t i = 0; i < positions.size(); i += 3) {
    const double x = positions[i], y = positions[i + 1], z = positions[i + 2];
    const int corner = x > 0.1 ? 1 : y > 0.1 ? 2 : z > 0.1 ? 3 : 0;
    EXPECT_NEAR(std::abs(x) + std::abs(y) + std::abs(z), corner == 0 ? 0.0 : 0.2, 1e-6);
    corners.insert(corner);
  }
  EXPECT_EQ(corners.size(), 4u);
  expectPose(part, {-0.7, -0.5, 0.3}, rows({0, -1, 0, 1, 0, 0, 0, 0, 1}));
}

void ReportScene::expectGripper() {
  const auto& entry = problem("moveit-0001");
  const auto& robot = data_->at("robots").at(entry["robot"].get<std::size_t>());
  std::vector<std::string> names;
  for (const auto& mesh : robot["meshes"]) names.push_back(mesh["link"]);
  // The seven UR10e link meshes, then the two gripper links (links in parent-before-child order).
  ASSERT_EQ(names.size(), 9u);
  EXPECT_EQ(names[7], "gripper");
  EXPECT_EQ(names[8], "finger");
  const auto& gripper = robot["meshes"][7];
  EXPECT_EQ(gripper["triangles"], 12);
  // The box's corners in the gripper's frame: +-(0.04, 0.03, 0.04) about (0, 0, 0.05).
  const auto corners = decodeBase64Array<float>(gripper["positions"]);
  for (std::size_t i = 0; i < corners.size(); i += 3) {
    EXPECT_NEAR(std::abs(corners[i]), 0.04, 1e-6);
    EXPECT_NEAR(std::abs(corners[i + 1]), 0.03, 1e-6);
    EXPECT_NEAR(std::abs(corners[i + 2] - 0.05), 0.04, 1e-6);
  }
  // At the start configuration the finger's frame is 0.1 m along the gripper frame's z axis.
  const auto poses = decodeBase64Array<float>(entry["endpoints"]["poses"]);
  ASSERT_EQ(poses.size(), 2u * 9u * 7u);  // start and goal, nine links, position + quaternion
  const float* g = &poses[7 * 7];
  const float* f = &poses[8 * 7];
  const double x = g[3], y = g[4], z = g[5], w = g[6];
  const Eigen::Vector3d zAxis(2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k] - g[k], 0.1 * zAxis[k], 1e-5);
  // The body held by tool0 (no geometry) rides on wrist_3_link, the nearest drawn link: placed by
  // wrist_3's pose it is 0.3 m along the gripper's (= tool0's) z axis.
  const auto& attached = entry["scene"]["attached"];
  ASSERT_EQ(attached.size(), 1u);
  EXPECT_EQ(attached[0]["link"], "wrist_3_link");
  EXPECT_EQ(attached[0]["shape"], "sphere");
  const float* w3 = &poses[6 * 7];
  const Eigen::Quaterniond wrist3(w3[6], w3[3], w3[4], w3[5]);
  const Eigen::Vector3d inWrist3(attached[0]["position"][0], attached[0]["position"][1], attached[0]["position"][2]);
  const Eigen::Vector3d held = Eigen::Vector3d(w3[0], w3[1], w3[2]) + wrist3 * inWrist3;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(held[k], g[k] + 0.3 * zAxis[k], 1e-5);
  // The scene-file problem names the same robot: drawn once.
  EXPECT_EQ(problem("stl")["robot"], entry["robot"]);
}

TEST_F(ReportScene, EveryObstacleKindAndTheGripperPosed) {
  ASSERT_NE(data_, nullptr) << "the campaign failed";
  expectMoveItPrimitives();
  expectSceneFileMesh();
  expectGripper();
}

// A campaign's scene.json with a key of the wrong type, or a mesh whose coordinates are not triples, is
// an error naming the file, not an internal error.
TEST_F(ReportScene, AMalformedSceneJsonIsAnErrorNamingTheFile) {
  ASSERT_NE(campaign_, nullptr) << "the campaign failed";
  const auto copy = arcplan::testing::freshTempDirectory("report_scene_bad") / "campaign";
  std::filesystem::copy(*campaign_, copy, std::filesystem::copy_options::recursive);
  std::filesystem::path sceneFile;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(copy / "paths")) {
    if (entry.path().filename() == "scene.json" && entry.path().string().find("moveit") != std::string::npos)
      sceneFile = entry.path();
  }
  ASSERT_FALSE(sceneFile.empty());
  const Json good = Json::parse(std::ifstream(sceneFile));
  const auto expectError = [&](const Json& bad, const std::string& part) {
    std::ofstream(sceneFile) << bad.dump();
    try {
      arcplan::report::campaignReportData(copy, copy / "report.html");
      ADD_FAILURE() << "no error for " << part;
    } catch (const arcplan::Error& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  Json wrongType = good;
  wrongType["start_joints"] = "home";
  expectError(wrongType, sceneFile.string());
  Json notTriples = good;
  for (auto& obstacle : notTriples["obstacles"]) {
    if (obstacle.value("shape", "") == "mesh") obstacle["vertices"].push_back(0.5);
  }
  expectError(notTriples, "expected multiples of 3");
}

TEST(RobotMeshes, MbmUr5EveryLinkWithGeometryIsDrawn) {
  const auto shared = arcplan::testing::sharedDataDirectory();
  ASSERT_FALSE(shared.empty()) << "ARCPLAN_SHARED_DATA (the MBM UR5) is needed";
  const auto urdfFile = shared / "mbm_ur5" / "ur5.urdf";
  // Links with a <collision> element, read from the URDF text.
  const std::string urdf = arcplan::testing::readFile(urdfFile);
  std::set<std::string> expected;
  const std::regex link("<link name=\"([^\"]+)\">([\\s\\S]*?)</link>");
  for (auto it = std::sregex_iterator(urdf.begin(), urdf.end(), link); it != std::sregex_iterator(); ++it) {
    if ((*it)[2].str().find("<collision") != std::string::npos) expected.insert((*it)[1]);
  }
  ASSERT_EQ(expected.size(), 18u);  // base to wrist_3 and ee_link, the FTS300, the Robotiq base, 8 finger links
  const auto meshes = arcplan::report::robotMeshesJson(arcplan::robot::loadRobotModel(urdfFile));
  std::set<std::string> drawn;
  for (const auto& mesh : meshes) {
    drawn.insert(mesh["link"].get<std::string>());
    EXPECT_LE(mesh["triangles"].get<std::size_t>(), arcplan::report::kMaxTrianglesPerMesh);
    EXPECT_GT(mesh["triangles"].get<std::size_t>(), 0u);
    if (mesh["link"] == "fts_robotside") {
      // A binary STL counts its triangles in the 4 bytes after its 80-byte header.
      std::ifstream stl(shared / "mbm_ur5" / "meshes" / "robotiq_fts300.stl", std::ios::binary);
      std::uint32_t count = 0;
      stl.seekg(80);
      stl.read(reinterpret_cast<char*>(&count), 4);
      EXPECT_EQ(mesh["source_triangles"], count);
      EXPECT_GT(count, arcplan::report::kMaxTrianglesPerMesh);  // so this one was thinned
    } else if (mesh["source_triangles"].get<std::size_t>() <= arcplan::report::kMaxTrianglesPerMesh) {
      EXPECT_EQ(mesh["triangles"], mesh["source_triangles"]) << mesh["link"];  // small meshes stay whole
    }
  }
  EXPECT_EQ(drawn, expected);
}

}  // namespace
