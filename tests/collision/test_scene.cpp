// Scene files (docs/formats.md): the thesis scenes as the issue states them, and every kind of bad
// input with a message that names the file, the line and the field.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "arcplan/collision/scene.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/primitive_mesh.h"
#include "support/command.h"

namespace {

using arcplan::collision::loadScene;
using arcplan::collision::Obstacle;
using arcplan::collision::Scene;

std::filesystem::path writeScene(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const auto file = dir / name;
  std::ofstream(file) << text;
  return file;
}

// The message of the arcplan::Error that loading `text` throws ("" if none).
std::string loadError(const std::string& text, const std::string& testName) {
  const auto dir = arcplan::testing::freshTempDirectory("scene_" + testName);
  try {
    loadScene(writeScene(dir, "scene.yaml", text));
  } catch (const arcplan::Error& e) {
    return e.what();
  }
  return "";
}

const char* kValidHeader = "name: t\nrobot: ur10e\n";

TEST(Scene, ThesisObstacleSceneHasTheIssuesNumbers) {
  const Scene scene = loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml");
  EXPECT_EQ(scene.name, "thesis_obstacle");
  EXPECT_TRUE(scene.robot.urdf.empty());
  ASSERT_EQ(scene.obstacles.size(), 2u);
  const Obstacle& table = scene.obstacles[0];
  EXPECT_EQ(table.shape, Obstacle::Shape::Box);
  // Table top at z = 0: centre z minus half the thickness.
  EXPECT_NEAR(table.pose.translation().z() + table.size.z() / 2.0, 0.0, 1e-12);
  const Obstacle& particle = scene.obstacles[1];
  EXPECT_EQ(particle.shape, Obstacle::Shape::Sphere);
  EXPECT_DOUBLE_EQ(particle.radius, 0.01);
  EXPECT_TRUE(particle.pose.translation().isApprox(Eigen::Vector3d(0.4375, -0.1, 0.32875), 1e-15));
  EXPECT_TRUE(particle.boundingCenter().isApprox(Eigen::Vector3d(0.4375, -0.1, 0.32875), 1e-15));
  EXPECT_DOUBLE_EQ(particle.boundingRadius(), 0.01);
  ASSERT_EQ(scene.allowedCollisions.size(), 2u);
  EXPECT_EQ(scene.allowedCollisions[0], std::make_pair(std::string("table"), std::string("base_link_inertia")));

  const auto& query = scene.query("A_to_B");
  ASSERT_TRUE(query.start.pose && query.goal.pose);
  const std::array<double, 6> a{0.4, -0.4, 0.25, 0, -M_PI, M_PI / 2}, b{0.5, 0.4, 0.46, 0, -M_PI, M_PI / 2};
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR((*query.start.pose)[i], a[i], 1e-15) << i;
    EXPECT_NEAR((*query.goal.pose)[i], b[i], 1e-15) << i;
  }
  ASSERT_TRUE(query.start.seed.has_value());
  EXPECT_NEAR((*query.start.seed)[0], -1.098, 1e-12);
  EXPECT_EQ(&scene.query(""), &scene.queries.front());
}

TEST(Scene, ThesisFreeSceneIsTheObstacleSceneWithoutTheParticle) {
  const Scene free = loadScene(arcplan::dataDirectory() / "scenes" / "thesis_free.yaml");
  const Scene obstacle = loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml");
  ASSERT_EQ(free.obstacles.size(), 1u);
  EXPECT_EQ(free.obstacles[0].name, "table");
  EXPECT_TRUE(free.obstacles[0].pose.isApprox(obstacle.obstacles[0].pose));
  EXPECT_EQ(free.allowedCollisions, obstacle.allowedCollisions);
  EXPECT_EQ(*free.query("A_to_B").goal.pose, *obstacle.query("A_to_B").goal.pose);
}

// A scene with every shape (the mesh a tiny ASCII STL so it needs no binary fixture), an rpy
// expression, an allowed pair and a joint query.
std::filesystem::path everyShapeScene(const std::filesystem::path& dir) {
  arcplan::robot::TriangleMesh mesh = arcplan::robot::cylinderMesh({0, 0, -1}, {0, 0, 1}, 0.5, 8);
  std::ofstream stl(dir / "post.stl");
  stl << "solid post\n";
  for (const auto& t : mesh.triangles) {
    stl << "facet normal 0 0 0\nouter loop\n";
    for (int k = 0; k < 3; ++k) stl << "vertex " << mesh.vertices[t[k]].transpose() << "\n";
    stl << "endloop\nendfacet\n";
  }
  stl << "endsolid post\n";
  stl.close();
  const auto file = writeScene(dir, "s.yaml", std::string(kValidHeader) + R"(obstacles:
  - {name: ball, sphere: {radius: 0.1}, position: [1, 2, 3]}
  - {name: crate, box: {size: [0.2, 0.4, 0.6]}, position: [0, 0, 0], rpy: [0, 0, pi/2]}
  - {name: pipe, cylinder: {radius: 0.05, length: 0.3}, position: [0.5, 0, 0]}
  - {name: post, mesh: {file: post.stl, scale: 0.1}, position: [0, 1, 0]}
allowed_collisions:
  - [ball, wrist_3_link]
queries:
  - name: joints
    start: {joints: [0, -pi/2, 0, -pi/2, 0, 0]}
    goal: {joints: [0.1, -1, 1, -1, 1, 0.5]}
  - name: pose
    start: {pose: [0.4, -0.4, 0.25, 0, -pi, pi/2], seed: [0, -1.5, 1.5, -1.5, -1.5, 0]}
    goal: {pose: [0.5, 0.4, 0.46, 0, -pi, pi/2]}
)");
  return file;
}

TEST(Scene, ReadsEveryShapeRpyExpressionsAndJointQueries) {
  const Scene scene = loadScene(everyShapeScene(arcplan::testing::freshTempDirectory("scene_shapes")));
  ASSERT_EQ(scene.obstacles.size(), 4u);
  EXPECT_EQ(scene.obstacles[1].shape, Obstacle::Shape::Box);
  // rpy yaw pi/2 turns x into y.
  EXPECT_TRUE((scene.obstacles[1].pose.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_NEAR(scene.obstacles[1].boundingRadius(), std::sqrt(0.1 * 0.1 + 0.2 * 0.2 + 0.3 * 0.3), 1e-12);
  EXPECT_NEAR(scene.obstacles[2].boundingRadius(), std::hypot(0.05, 0.15), 1e-12);
  const Obstacle& post = scene.obstacles[3];
  EXPECT_EQ(post.shape, Obstacle::Shape::Mesh);
  ASSERT_TRUE(post.meshData != nullptr);
  // Scaled by 0.1: the octagonal prism spans z in [-0.1, 0.1], its corners at radius 0.05/cos(pi/8).
  EXPECT_NEAR(post.boundingRadius(), std::hypot(0.05 / std::cos(M_PI / 8), 0.1), 1e-6);
  EXPECT_TRUE(post.boundingCenter().isApprox(Eigen::Vector3d(0, 1, 0), 1e-6));
  const auto& query = scene.query("joints");
  ASSERT_TRUE(query.start.joints.has_value());
  EXPECT_NEAR((*query.start.joints)[1], -M_PI / 2, 1e-15);
  EXPECT_FALSE(query.start.pose.has_value());
}

void expectSameEndpoint(const arcplan::collision::QueryEndpoint& read, const arcplan::collision::QueryEndpoint& given) {
  ASSERT_EQ(read.pose.has_value(), given.pose.has_value());
  ASSERT_EQ(read.seed.has_value(), given.seed.has_value());
  ASSERT_EQ(read.joints.has_value(), given.joints.has_value());
  for (int i = 0; i < 6; ++i) {
    if (given.pose) {
      EXPECT_NEAR((*read.pose)[i], (*given.pose)[i], 1e-14);
    }
    if (given.seed) {
      EXPECT_NEAR((*read.seed)[i], (*given.seed)[i], 1e-14);
    }
    if (given.joints) {
      EXPECT_NEAR((*read.joints)[i], (*given.joints)[i], 1e-14);
    }
  }
}

// Field by field; numbers to the 15 significant digits the writer keeps.
void expectSameScene(const Scene& read, const Scene& given) {
  EXPECT_EQ(read.name, given.name);
  EXPECT_EQ(read.robot.urdf, given.robot.urdf);
  EXPECT_EQ(read.robot.urType, given.robot.urType);
  EXPECT_EQ(read.robot.srdf, given.robot.srdf);
  EXPECT_EQ(read.robot.chain.tipLink, given.robot.chain.tipLink);
  ASSERT_EQ(read.robot.chain.tcpOffset.has_value(), given.robot.chain.tcpOffset.has_value());
  if (given.robot.chain.tcpOffset) {
    EXPECT_TRUE(read.robot.chain.tcpOffset->isApprox(*given.robot.chain.tcpOffset, 1e-14));
  }
  ASSERT_EQ(read.obstacles.size(), given.obstacles.size());
  for (std::size_t i = 0; i < given.obstacles.size(); ++i) {
    SCOPED_TRACE(given.obstacles[i].name);
    const Obstacle& a = read.obstacles[i];
    const Obstacle& b = given.obstacles[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.shape, b.shape);
    EXPECT_NEAR(a.radius, b.radius, 1e-15);
    EXPECT_NEAR(a.length, b.length, 1e-15);
    EXPECT_TRUE(a.size.isApprox(b.size, 1e-14));
    EXPECT_EQ(a.meshFile, b.meshFile);
    EXPECT_TRUE(a.meshScale.isApprox(b.meshScale, 1e-14));
    EXPECT_TRUE(a.pose.isApprox(b.pose, 1e-14));
  }
  EXPECT_EQ(read.allowedCollisions, given.allowedCollisions);
  ASSERT_EQ(read.queries.size(), given.queries.size());
  for (std::size_t i = 0; i < given.queries.size(); ++i) {
    SCOPED_TRACE(given.queries[i].name);
    EXPECT_EQ(read.queries[i].name, given.queries[i].name);
    expectSameEndpoint(read.queries[i].start, given.queries[i].start);
    expectSameEndpoint(read.queries[i].goal, given.queries[i].goal);
  }
}

TEST(SceneWriter, WrittenScenesReadBackAsTheSameScene) {
  const auto dir = arcplan::testing::freshTempDirectory("scene_round_trip");
  // arcplan's UR10e from its URDF with an SRDF and a TCP offset: the robot entry as a mapping.
  std::ofstream(dir / "r.srdf") << "<robot name=\"ur10e\"><disable_collisions link1=\"wrist_1_link\" "
                                   "link2=\"wrist_3_link\" reason=\"Never\"/></robot>";
  const auto robotScene = dir / "robot_entry.yaml";
  std::ofstream(robotScene) << "name: robot_entry\nrobot: {urdf: " << arcplan::robot::ur10eUrdfPath().string()
                            << ", srdf: r.srdf, tcp: {link: flange, offset: [0, 0.01, 0.2, 0, 0, pi/4]}}\n";
  for (const auto& source :
       {everyShapeScene(dir), arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml", robotScene}) {
    SCOPED_TRACE(source.string());
    const Scene scene = loadScene(source);
    const auto written = dir / ("written_" + source.filename().string());
    arcplan::collision::writeScene(scene, written);
    expectSameScene(loadScene(written), scene);
  }
}

TEST(SceneErrors, UnknownFile) {
  try {
    loadScene("/nonexistent/scene.yaml");
    FAIL() << "no error";
  } catch (const arcplan::Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.yaml does not exist"), std::string::npos) << e.what();
  }
}

TEST(SceneErrors, MalformedYamlSaysWhere) {
  const std::string message = loadError("name: t\nobstacles:\n  - {name: a, sphere: {radius: 0.1}\n", "malformed");
  EXPECT_NE(message.find("scene.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("malformed YAML"), std::string::npos) << message;
  EXPECT_NE(message.find(":4:"), std::string::npos) << message;  // the flow map is still open at the end
}

TEST(SceneErrors, UnknownShapeKeyAndMissingShape) {
  const std::string unknown = loadError(
      std::string(kValidHeader) + "obstacles:\n  - name: c\n    cone: {radius: 1}\n    position: [0, 0, 0]\n", "cone");
  EXPECT_NE(unknown.find("scene.yaml:5:5: obstacles[0]: unknown key 'cone'"), std::string::npos) << unknown;
  const std::string none =
      loadError(std::string(kValidHeader) + "obstacles:\n  - {name: c, position: [0, 0, 0]}\n", "noshape");
  EXPECT_NE(none.find("obstacles[0] ('c'): no shape"), std::string::npos) << none;
}

TEST(SceneErrors, MissingRadius) {
  const std::string message = loadError(
      std::string(kValidHeader) + "obstacles:\n  - {name: ball, sphere: {}, position: [0, 0, 0]}\n", "radius");
  EXPECT_NE(message.find(":4:"), std::string::npos) << message;
  EXPECT_NE(message.find("obstacles[0] ('ball').sphere: missing 'radius'"), std::string::npos) << message;
}

TEST(SceneErrors, NegativeSize) {
  const std::string message = loadError(
      std::string(kValidHeader) + "obstacles:\n  - {name: crate, box: {size: [1, -2, 1]}, position: [0, 0, 0]}\n",
      "size");
  EXPECT_NE(message.find("obstacles[0] ('crate').box.size[1]: expected a positive number, got -2"), std::string::npos)
      << message;
}

TEST(SceneErrors, WrongVectorLength) {
  const std::string message = loadError(
      std::string(kValidHeader) + "obstacles:\n  - {name: ball, sphere: {radius: 1}, position: [0, 0]}\n", "length");
  EXPECT_NE(message.find("obstacles[0] ('ball').position: expected a list of 3 numbers, got 2"), std::string::npos)
      << message;
  const std::string seed = loadError(std::string(kValidHeader) +
                                         "queries:\n  - name: q\n    start: {pose: [0, 0, 0, 0, 0, 0], seed: [1]}\n"
                                         "    goal: {joints: [0, 0, 0, 0, 0, 0]}\n",
                                     "seed");
  EXPECT_NE(seed.find("queries[0].start.seed: expected a list of 6 numbers, got 1"), std::string::npos) << seed;
}

TEST(SceneErrors, NotANumber) {
  const std::string message = loadError(
      std::string(kValidHeader) + "obstacles:\n  - {name: ball, sphere: {radius: big}, position: [0, 0, 0]}\n", "nan");
  EXPECT_NE(message.find("sphere.radius: expected a number or an expression like -pi/2, got 'big'"), std::string::npos)
      << message;
}

TEST(SceneErrors, MeshNotFound) {
  const std::string message = loadError(
      std::string(kValidHeader) + "obstacles:\n  - {name: m, mesh: {file: missing.stl}, position: [0, 0, 0]}\n",
      "mesh");
  EXPECT_NE(message.find("obstacles[0] ('m').mesh.file:"), std::string::npos) << message;
  EXPECT_NE(message.find("missing.stl"), std::string::npos) << message;
}

TEST(SceneErrors, UnknownLinkOrObstacleInAllowedCollisions) {
  const std::string message =
      loadError(std::string(kValidHeader) + "allowed_collisions:\n  - [wrist_9_link, base_link]\n", "acm");
  EXPECT_NE(message.find("allowed_collisions[0]: unknown link or obstacle 'wrist_9_link'"), std::string::npos)
      << message;
}

TEST(SceneErrors, DuplicateAndLinkNamedObstacles) {
  const std::string duplicate = loadError(std::string(kValidHeader) +
                                              "obstacles:\n  - {name: a, sphere: {radius: 1}, position: [0, 0, 0]}\n"
                                              "  - {name: a, sphere: {radius: 1}, position: [0, 0, 0]}\n",
                                          "duplicate");
  EXPECT_NE(duplicate.find("obstacles[1].name: duplicate obstacle name 'a'"), std::string::npos) << duplicate;
  const std::string link = loadError(
      std::string(kValidHeader) + "obstacles:\n  - {name: tool0, sphere: {radius: 1}, position: [0, 0, 0]}\n", "link");
  EXPECT_NE(link.find("'tool0' is already the name of a robot link"), std::string::npos) << link;
}

TEST(SceneErrors, QueryEndpointNeedsPoseOrJoints) {
  const std::string message = loadError(std::string(kValidHeader) +
                                            "queries:\n  - name: q\n    start: {seed: [0, 0, 0, 0, 0, 0]}\n"
                                            "    goal: {joints: [0, 0, 0, 0, 0, 0]}\n",
                                        "endpoint");
  EXPECT_NE(message.find("queries[0].start: expected exactly one of 'pose'"), std::string::npos) << message;
}

TEST(SceneErrors, UnknownQueryListsTheKnownOnes) {
  const Scene scene = loadScene(arcplan::dataDirectory() / "scenes" / "thesis_free.yaml");
  try {
    scene.query("C_to_D");
    FAIL() << "no error";
  } catch (const arcplan::Error& e) {
    EXPECT_NE(std::string(e.what()).find("has no query 'C_to_D'; queries: A_to_B"), std::string::npos) << e.what();
  }
}

}  // namespace
