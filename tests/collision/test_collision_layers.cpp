// The bounding layers in front of FCL's meshes (docs/collision.md, "Layers"): convex hulls that
// contain every mesh vertex, rigid pairs measured once, and hasClearance. Each answer is compared
// with a model that has every layer off (FCL on the meshes only: `--collision exact-only`), on the
// thesis scene and, where the shared data is, on MotionBenchMaker's UR5 + Robotiq 85 problems.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/kinematics.h"
#include "convex_hull.h"           // collision/src
#include "model_implementation.h"  // collision/src
#include "support/collision_options.h"
#include "support/command.h"
#include "support/joint_states.h"

namespace {

using namespace arcplan::collision;
namespace fs = std::filesystem;

fs::path mbmFolder() { return arcplan::testing::sharedDataDirectory() / "mbm_ur5"; }

// Problems of each MBM family (the shared data is optional: an empty list without it).
std::vector<Scene> mbmScenes(int perFamily) {
  std::vector<Scene> scenes;
  if (!fs::exists(mbmFolder() / "problems")) return scenes;
  const MoveItRobot robot{mbmFolder() / "ur5.urdf", mbmFolder() / "ur5.srdf"};
  for (const char* family :
       {"bookshelf_small_ur5", "bookshelf_tall_ur5", "bookshelf_thin_ur5", "box_ur5", "table_pick_ur5"}) {
    for (int k = 1; k <= perFamily; ++k) {
      char number[8];
      std::snprintf(number, sizeof number, "%04d", 37 * k % 100 + 1);
      const fs::path folder = mbmFolder() / "problems" / family;
      scenes.push_back(loadMoveItProblem(folder / ("scene" + std::string(number) + ".yaml"),
                                         folder / ("request" + std::string(number) + ".yaml"), robot)
                           .scene);
    }
  }
  return scenes;
}

// The thesis scene and one problem per MBM family (the FCL-only reference costs ~10 ms per MBM state).
std::vector<Scene> testScenes() {
  std::vector<Scene> scenes{loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml")};
  for (auto& scene : mbmScenes(1)) scenes.push_back(std::move(scene));
  return scenes;
}

using arcplan::testing::exactOnly;

TEST(CollisionLayers, HullOfACubeIsTheCubeAndContainsEveryPoint) {
  // Independent reference: the cube's 8 corners are the hull's vertices, 12 triangles, and its inner
  // points (the centre, face centres) are no vertices.
  std::vector<Eigen::Vector3d> points;
  for (int corner = 0; corner < 8; ++corner)
    points.emplace_back(corner & 1 ? 0.1 : -0.1, corner & 2 ? 0.2 : -0.2, corner & 4 ? 0.3 : -0.3);
  points.emplace_back(0.0, 0.0, 0.0);
  points.emplace_back(0.1, 0.0, 0.0);
  const auto hull = detail::containingHull(points);
  ASSERT_TRUE(hull);
  EXPECT_EQ(hull->getVertices().size(), 8u);
  EXPECT_EQ(hull->getFaceCount(), 12);
  EXPECT_LE(detail::largestOutside(*hull, points), 0.0);
  // Pushed out by at most a rounding: a point 1e-9 outside a face is outside the hull.
  EXPECT_GT(detail::largestOutside(*hull, {Eigen::Vector3d(0.1 + 1e-9, 0.0, 0.0)}), 0.0);
  EXPECT_FALSE(detail::containingHull({points[0], points[1], points[2], points[3]}));  // a flat face: no hull
}

TEST(CollisionLayers, EveryPartHullContainsEveryVertexOfItsPart) {
  auto scenes = testScenes();
  scenes.resize(std::min<std::size_t>(scenes.size(), 2));  // the robot's parts are the same in every MBM scene
  for (const Scene& scene : scenes) {
    const auto model = makeCollisionModel(scene);
    const auto& impl = detail::implementationOf(*model);
    int hulls = 0;
    for (const auto& part : impl.robotParts) {
      if (part.hullPoints.empty() || part.convexGeometry) continue;
      ASSERT_TRUE(part.hullGeometry) << "a mesh part of " << model->linkNames()[part.body] << " has no hull";
      const auto& hull = static_cast<const fcl::Convexd&>(*part.hullGeometry);
      EXPECT_LE(detail::largestOutside(hull, part.hullPoints), 0.0) << model->linkNames()[part.body];
      ++hulls;
    }
    if (!scene.robot.isBuiltIn()) {
      EXPECT_GT(hulls, 10);  // the UR5 and Robotiq meshes are not convex
    }
  }
}

// Two balls held by wrist_3_link (attached bodies) are a rigid pair: their distance is the centres'
// distance less the radii in every configuration, and every query reports it.
TEST(CollisionLayers, RigidPairsKeepTheirDistance) {
  Scene scene = loadScene(arcplan::dataDirectory() / "scenes" / "thesis_free.yaml");
  for (const auto& [name, x, radius] : {std::tuple{"ball_a", 0.0, 0.02}, std::tuple{"ball_b", 0.07, 0.03}}) {
    AttachedObstacle held;
    held.link = "wrist_3_link";
    held.body.name = name;
    held.body.shape = Obstacle::Shape::Sphere;
    held.body.radius = radius;
    held.body.pose.translation() = Eigen::Vector3d(x, 0.0, 0.2);
    scene.attachedObstacles.push_back(held);
    scene.allowedCollisions.emplace_back(name, "wrist_3_link");
    scene.allowedCollisions.emplace_back(name, "wrist_2_link");
    scene.allowedCollisions.emplace_back(name, "table");
  }
  const double expected = 0.07 - 0.02 - 0.03;
  const auto model = makeCollisionModel(scene);
  const auto& impl = detail::implementationOf(*model);
  int rigid = 0;
  for (const auto& group : impl.selfGroups) {
    if (!group.rigid) continue;
    ++rigid;
    EXPECT_EQ(model->linkNames()[group.firstBody], "ball_a");
    EXPECT_EQ(model->linkNames()[group.secondBody], "ball_b");
    EXPECT_NEAR(group.rigidDistance, expected, 1e-9);
  }
  EXPECT_EQ(rigid, 1);
  CollisionData data(*model);
  std::mt19937_64 random(5);
  for (int k = 0; k < 20; ++k) {
    const Eigen::VectorXd q = arcplan::testing::randomJointState(model->robot(), random);
    const DistanceReport report = distance(*model, data, q);
    EXPECT_LE(report.selfDistance, expected + 1e-9);
    // Asked of self pairs too (the per-kind query under hasClearance), the held balls are closer than that; a
    // clearance asks at most 1 mm of them (collision_model.h), which they keep.
    EXPECT_FALSE(detail::keepsDistances(*model, data, q, expected + 0.001, expected + 0.001));
    EXPECT_EQ(hasClearance(*model, data, q, expected + 0.001),
              report.obstacleDistance >= expected + 0.001 && report.selfDistance >= 0.001);
  }
}

// A rigid pair's distance is the smallest of its part pairs' (measureRigidPairs skips the part pairs whose
// bounds cannot lower it): against the exact distance (partsDistance, FCL on the meshes and shapes) of
// every part pair at the home posture. MBM's force sensor against the gripper: several groups of many
// part pairs.
TEST(CollisionLayers, RigidPairDistanceIsTheNearestOfAllItsPartPairs) {
  const auto scenes = mbmScenes(1);
  ASSERT_FALSE(scenes.empty()) << "MBM problems expected under " << mbmFolder();
  const auto model = makeCollisionModel(scenes.front());
  const auto& impl = detail::implementationOf(*model);
  arcplan::robot::KinematicsData kinematics(model->robot());
  arcplan::robot::forwardKinematics(model->robot(), Eigen::VectorXd::Zero(model->robot().dof()), kinematics);
  const auto pose = [&](int i) { return kinematics.linkPoses[impl.robotPartLink[i]] * impl.robotParts[i].offset; };
  int rigid = 0, partPairs = 0;
  for (const auto& group : impl.selfGroups) {
    if (!group.rigid) continue;
    ++rigid;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& [i, j] : group.parts) {
      nearest = std::min(
          nearest, detail::partsDistance(impl.robotParts[i], pose(i), impl.robotParts[j], pose(j), true, exactOnly()));
      ++partPairs;
    }
    EXPECT_NEAR(group.rigidDistance, nearest, 2e-6)
        << model->linkNames()[group.firstBody] << "–" << model->linkNames()[group.secondBody];
  }
  EXPECT_GE(rigid, 5);
  EXPECT_GT(partPairs, 10 * rigid);  // groups of many part pairs, most of them skipped by their bounds
}

// The layered model's answers against FCL alone: isCollisionFree, hasClearance against the rule on FCL's
// distances (obstacles at least c, self pairs at least min(c, 1 mm)), the per-kind query under it with c for
// both kinds against distance().minimum() >= c, and distance() itself, on seeded random states.
TEST(CollisionLayers, AnswersAreThoseOfFclOnTheMeshes) {
  for (const Scene& scene : testScenes()) {
    const auto layered = makeCollisionModel(scene), exact = makeCollisionModel(scene, exactOnly());
    CollisionData layeredData(*layered), exactData(*exact);
    std::mt19937_64 random(17);
    int free = 0, clear = 0;
    const int states = scene.robot.isBuiltIn() ? 400 : 60;
    for (int k = 0; k < states; ++k) {
      const Eigen::VectorXd q = arcplan::testing::randomJointState(exact->robot(), random);
      const bool expectedFree = isCollisionFree(*exact, exactData, q);
      ASSERT_EQ(isCollisionFree(*layered, layeredData, q), expectedFree) << scene.name << " state " << k;
      free += expectedFree;
      const DistanceReport expectedReport = distance(*exact, exactData, q);
      const double expectedDistance = expectedReport.minimum();
      ASSERT_NEAR(distance(*layered, layeredData, q).minimum(), expectedDistance, 1e-9) << scene.name;
      for (const double c : {0.001, 0.01, 0.05}) {
        const bool rule = expectedReport.obstacleDistance >= c && expectedReport.selfDistance >= std::min(c, 0.001);
        ASSERT_EQ(hasClearance(*layered, layeredData, q, c), rule)
            << scene.name << " state " << k << " clearance " << c << " distance " << expectedDistance;
        ASSERT_EQ(detail::keepsDistances(*layered, layeredData, q, c, c), expectedDistance >= c)
            << scene.name << " state " << k << " clearance " << c << " distance " << expectedDistance;
      }
      clear += expectedDistance >= 0.01;
    }
    EXPECT_GT(free, 0) << scene.name;  // both answers occur
    EXPECT_LT(free, states) << scene.name;
    EXPECT_GT(clear, 0) << scene.name;
  }
}

TEST(CollisionLayers, HasClearanceRefusesANonPositiveClearance) {
  const auto model = makeCollisionModel(loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml"));
  CollisionData data(*model);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(6);
  EXPECT_THROW(hasClearance(*model, data, q, 0.0), arcplan::Error);
  EXPECT_THROW(hasClearance(*model, data, q, NAN), arcplan::Error);
  EXPECT_THROW(hasClearance(*model, data, Eigen::VectorXd::Zero(5), 0.01), arcplan::Error);
}

// Certified motions keep their guarantee with the layers: a motion the layered model accepts has
// no colliding state (exact model, 301 states: 1 mrad apart), and a motion with a colliding state
// is rejected.
TEST(CollisionLayers, CertifiedMotionsStayCertified) {
  for (const Scene& scene : testScenes()) {
    const auto layered = makeCollisionModel(scene), exact = makeCollisionModel(scene, exactOnly());
    CollisionData layeredData(*layered), exactData(*exact);
    std::mt19937_64 random(23);
    std::normal_distribution<double> gaussian;
    MotionCheckOptions options;
    options.minimumClearance = 0.01;
    int accepted = 0, checked = 0;
    while (checked < 6) {
      const Eigen::VectorXd start = arcplan::testing::randomJointState(exact->robot(), random);
      if (!isCollisionFree(*exact, exactData, start)) continue;
      Eigen::VectorXd direction(start.size());
      for (int j = 0; j < direction.size(); ++j) direction[j] = gaussian(random);
      const Eigen::VectorXd end = start + 0.3 * direction.normalized();
      ++checked;
      bool collides = false;
      for (int k = 0; k <= 300 && !collides; ++k)
        collides = !isCollisionFree(*exact, exactData, start + (k / 300.0) * (end - start));
      const bool free = isMotionCollisionFree(*layered, layeredData, start, end, nullptr, options);
      if (collides) {
        EXPECT_FALSE(free) << scene.name;
      }
      // Accepted: minimumClearance kept at every sampled state, less the exact distances' 1e-6 m, by the
      // state check (AnswersAreThoseOfFclOnTheMeshes; FCL distances here took 100 s instead of 15 s).
      for (int k = 0; k <= 300 && free; ++k) {
        const Eigen::VectorXd q = start + (k / 300.0) * (end - start);
        ASSERT_TRUE(hasClearance(*layered, layeredData, q, options.minimumClearance - 1e-6)) << scene.name << " " << k;
      }
      accepted += free;
    }
    EXPECT_GT(accepted, 0) << scene.name;
  }
}

}  // namespace
