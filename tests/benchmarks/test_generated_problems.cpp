// The generated suite's problems: reproducible from the seed, valid and reachable, obstacles where
// the generator promises them, and scene files that read back identically.
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "arcplan/benchmarks/generated_problems.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_inverse_kinematics.h"
#include "support/command.h"
#include "support/joint_states.h"
#include "support/segment_distance.h"

namespace arcplan::benchmarks {
namespace {

using arcplan::testing::distanceToSegment;

// A small mix of every family keeps the test fast; the full suite uses the same code paths.
GeneratorSettings smallSettings(std::uint64_t seed) {
  GeneratorSettings settings;
  settings.seed = seed;
  settings.lineObstacles = 6;
  settings.pillars = 2;
  settings.shelves = 2;
  settings.clutter = 1;
  settings.armBlocked = 1;
  settings.walls = 1;
  settings.nearEndpoint = 1;
  settings.tallPillars = 1;
  settings.deepShelves = 1;
  settings.forearmBeams = 1;
  settings.lintelGates = 1;
  settings.tiltedTools = 1;
  return settings;
}

std::vector<std::string> asYaml(const std::vector<Problem>& problems) {
  std::vector<std::string> documents;
  for (const auto& problem : problems) documents.push_back(collision::sceneToYaml(problem.scene));
  return documents;
}

const std::vector<Problem>& problemsOfSeed7() {
  static const auto problems = generateProblems(smallSettings(7));
  return problems;
}

TEST(GeneratedProblems, SameSeedGivesIdenticalProblems) {
  const auto again = generateProblems(smallSettings(7));
  ASSERT_EQ(again.size(), problemsOfSeed7().size());
  EXPECT_EQ(asYaml(again), asYaml(problemsOfSeed7()));
  for (std::size_t i = 0; i < again.size(); ++i) {
    EXPECT_EQ(again[i].name, problemsOfSeed7()[i].name);
    EXPECT_EQ(again[i].origin, problemsOfSeed7()[i].origin);
  }
}

TEST(GeneratedProblems, OtherSeedGivesOtherProblems) {
  const auto other = generateProblems(smallSettings(8));
  const auto a = asYaml(problemsOfSeed7()), b = asYaml(other);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NE(a[i], b[i]) << "problem " << i;
}

TEST(GeneratedProblems, FamiliesAreIndependentStreams) {
  // Asking for more line problems leaves pillars and shelves as they were.
  auto settings = smallSettings(7);
  settings.lineObstacles = 7;
  const auto more = generateProblems(settings);
  ASSERT_EQ(more.size(), problemsOfSeed7().size() + 1);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(collision::sceneToYaml(more[more.size() - 1 - i].scene),
              collision::sceneToYaml(problemsOfSeed7()[problemsOfSeed7().size() - 1 - i].scene));
  }
}

TEST(GeneratedProblems, NamesAndFamiliesAsRequested) {
  const auto& problems = problemsOfSeed7();
  ASSERT_EQ(problems.size(), 19u);
  std::set<std::string> names;
  for (const auto& problem : problems) names.insert(problem.name);
  EXPECT_EQ(names.size(), problems.size());
  EXPECT_EQ(problems[0].name, "line-sphere-000");
  EXPECT_EQ(problems[1].name, "line-box-001");
  EXPECT_EQ(problems[2].name, "line-cylinder-002");
  EXPECT_EQ(problems[6].name, "pillar-000");
  EXPECT_EQ(problems[9].name, "shelf-001");
  const std::vector<std::string> workcell{"clutter-000",      "arm-blocked-000", "wall-000",
                                          "near-end-000",     "pillar-tall-000", "shelf-deep-000",
                                          "forearm-beam-000", "lintel-gate-000", "tilted-tool-000"};
  for (std::size_t i = 0; i < workcell.size(); ++i) EXPECT_EQ(problems[10 + i].name, workcell[i]);
  for (const auto& problem : problems) {
    EXPECT_EQ(problem.query, "main");
    ASSERT_EQ(problem.scene.queries.size(), 1u);
    EXPECT_TRUE(problem.scene.queries[0].start.joints.has_value());
    EXPECT_TRUE(problem.scene.queries[0].goal.joints.has_value());
  }
}

// (tilted-tool holds the tool 30-70 degrees off vertical: test_arm_contact_problems.cpp.)
TEST(GeneratedProblems, StartAndGoalAreValidReachableToolDownPoses) {
  const auto& model = robot::ur10e();
  const robot::UrInverseKinematics ik(model);
  const Eigen::Vector3d down(0.0, 0.0, -1.0);
  for (const auto& problem : problemsOfSeed7()) {
    SCOPED_TRACE(problem.name);
    const auto collisionModel = collision::makeCollisionModel(problem.scene);
    collision::CollisionData data(*collisionModel);
    const auto& query = problem.scene.queries.front();
    for (const auto& q : {*query.start.joints, *query.goal.joints}) {
      arcplan::testing::expectWithinJointLimits(model, q);
      // Every colliding pair, not just the first: none may be reported.
      const auto report = collision::collide(*collisionModel, data, q);
      EXPECT_TRUE(report.valid) << (report.collisions.empty()
                                        ? ""
                                        : report.collisions[0].first + " / " + report.collisions[0].second);
      // More room than the built-in suites' 1 cm clearance, so every planner may start and end there.
      EXPECT_GE(collision::distance(*collisionModel, data, q).minimum(), 0.012);
      const auto pose = robot::tipPose(model, q);
      if (problem.kind != "tilted-tool") {
        EXPECT_NEAR((pose.linear() * Eigen::Vector3d::UnitZ() - down).norm(), 0.0, 1e-9) << "tool not pointing down";
      }
      EXPECT_GT(pose.translation().z(), 0.1);
      // Reachable: the analytic IK reproduces this configuration from its pose.
      bool found = false;
      for (const auto& solution : ik.solveAll(pose)) found = found || (solution - q).norm() < 1e-6;
      EXPECT_TRUE(found);
    }
    // The straight line between them is walked on one IK branch.
    EXPECT_EQ(ik.branchOf(*query.start.joints), ik.branchOf(*query.goal.joints));
  }
}

TEST(GeneratedProblems, LineObstaclesSitOnOrNearTheStraightTcpLine) {
  const auto& model = robot::ur10e();
  int blocking = 0, lineProblems = 0;
  for (const auto& problem : problemsOfSeed7()) {
    if (problem.kind.rfind("line-", 0) != 0) continue;
    SCOPED_TRACE(problem.name);
    ++lineProblems;
    const auto& query = problem.scene.queries.front();
    const Eigen::Vector3d a = robot::tipPose(model, *query.start.joints).translation();
    const Eigen::Vector3d b = robot::tipPose(model, *query.goal.joints).translation();
    ASSERT_EQ(problem.scene.obstacles.size(), 2u);  // table + obstacle
    const auto& obstacle = problem.scene.obstacles[1];
    const double offLine = distanceToSegment(obstacle.boundingCenter(), a, b);
    EXPECT_LE(offLine, 1.2 * obstacle.boundingRadius() + 1e-9);
    EXPECT_GE((obstacle.boundingCenter() - a).norm(), obstacle.boundingRadius() + 0.15 - 1e-9);
    EXPECT_GE((obstacle.boundingCenter() - b).norm(), obstacle.boundingRadius() + 0.15 - 1e-9);
    if (offLine < obstacle.boundingRadius()) ++blocking;
  }
  EXPECT_EQ(lineProblems, 6);
  EXPECT_GE(blocking, 1) << "some obstacles must sit on the line";
}

TEST(GeneratedProblems, ClutteredScenesAreTallerThanAnyArcDetour) {
  for (const auto& problem : problemsOfSeed7()) {
    if (problem.kind == "pillar") {
      const auto& pillar = problem.scene.obstacles.back();
      EXPECT_EQ(pillar.shape, collision::Obstacle::Shape::Cylinder);
      EXPECT_NEAR(pillar.pose.translation().z() - pillar.length / 2, 0.0, 1e-12);  // stands on the table
      EXPECT_GE(pillar.length, 1.5);
    } else if (problem.kind == "shelf") {
      EXPECT_EQ(problem.scene.obstacles.size(), 7u);  // table, back, 2 sides, 3 boards
    }
  }
}

TEST(GeneratedProblems, WorkcellFamiliesHaveTheObstaclesTheyPromise) {
  const auto& model = robot::ur10e();
  const robot::UrInverseKinematics ik(model);
  for (const auto& problem : problemsOfSeed7()) {
    SCOPED_TRACE(problem.name);
    const auto& query = problem.scene.queries.front();
    const Eigen::Vector3d a = robot::tipPose(model, *query.start.joints).translation();
    const Eigen::Vector3d b = robot::tipPose(model, *query.goal.joints).translation();
    const auto& obstacles = problem.scene.obstacles;  // the table first
    if (problem.kind == "clutter") {
      EXPECT_GE(obstacles.size(), 3u);
      EXPECT_LE(obstacles.size(), 6u);
      for (std::size_t i = 1; i < obstacles.size(); ++i) {
        EXPECT_LT(distanceToSegment(obstacles[i].pose.translation(), a, b), 0.13);
      }
    } else if (problem.kind == "arm-blocked") {
      // The tool's line keeps 5 cm from the body's ball, but the arm following it hits the body
      // (walked here again with the IK, 5 mm steps).
      const auto& body = obstacles.back();
      EXPECT_GT(distanceToSegment(body.boundingCenter(), a, b), body.boundingRadius() + 0.05);
      const auto collisionModel = collision::makeCollisionModel(problem.scene);
      collision::CollisionData data(*collisionModel);
      robot::Vector6 q = *query.start.joints;
      bool hit = false;
      Eigen::Isometry3d pose = robot::tipPose(model, q);
      for (int k = 1; k <= 400 && !hit; ++k) {
        pose.translation() = a + (b - a) * (k / 400.0);
        q = *ik.solveNearest(pose, q);
        hit = !collision::isCollisionFree(*collisionModel, data, q);
      }
      EXPECT_TRUE(hit);
    } else if (problem.kind == "wall") {
      const auto& wall = obstacles.back();
      EXPECT_EQ(wall.shape, collision::Obstacle::Shape::Box);
      EXPECT_NEAR(wall.pose.translation().z() - wall.size.z() / 2, 0.0, 1e-12);  // stands on the table
      EXPECT_GT(wall.size.z(), std::max(a.z(), b.z()) + 0.05 - 1e-12);           // higher than the line
      EXPECT_LT(distanceToSegment(Eigen::Vector3d(wall.pose.translation().x(), wall.pose.translation().y(), 0.0),
                                  Eigen::Vector3d(a.x(), a.y(), 0.0), Eigen::Vector3d(b.x(), b.y(), 0.0)),
                1e-9);  // across it
    } else if (problem.kind == "near-end") {
      const Eigen::Vector3d c = obstacles.back().pose.translation();
      EXPECT_LT(std::min((c - a).norm(), (c - b).norm()), 0.16);
    } else if (problem.kind == "pillar-tall") {
      EXPECT_NEAR(obstacles.back().length, 2.0, 1e-12);
      EXPECT_GE(obstacles.back().radius, 0.08);
    } else if (problem.kind == "shelf-deep") {
      EXPECT_GE(obstacles[2].size.x(), 0.38);  // a side panel: depth along the line
    }
  }
}

TEST(GeneratedProblems, SceneYamlReadsBackAsTheSameScene) {
  const auto dir = testing::freshTempDirectory("generated_yaml");
  for (const auto& problem : problemsOfSeed7()) {
    SCOPED_TRACE(problem.name);
    const auto file = dir / (problem.name + ".yaml");
    writeFileAtomically(file, collision::sceneToYaml(problem.scene));
    const auto loaded = collision::loadScene(file);
    ASSERT_EQ(loaded.obstacles.size(), problem.scene.obstacles.size());
    for (std::size_t i = 0; i < loaded.obstacles.size(); ++i) {
      const auto& original = problem.scene.obstacles[i];
      const auto& read = loaded.obstacles[i];
      EXPECT_EQ(read.name, original.name);
      EXPECT_EQ(read.shape, original.shape);
      EXPECT_NEAR(read.radius, original.radius, 1e-12);
      EXPECT_NEAR(read.length, original.length, 1e-12);
      EXPECT_NEAR((read.size - original.size).norm(), 0.0, 1e-12);
      EXPECT_NEAR((read.pose.translation() - original.pose.translation()).norm(), 0.0, 1e-12);
      EXPECT_NEAR(robot::rotationDistance(read.pose.linear(), original.pose.linear()), 0.0, 1e-9);
    }
    ASSERT_EQ(loaded.queries.size(), 1u);
    EXPECT_NEAR((*loaded.queries[0].start.joints - *problem.scene.queries[0].start.joints).norm(), 0.0, 1e-12);
    EXPECT_NEAR((*loaded.queries[0].goal.joints - *problem.scene.queries[0].goal.joints).norm(), 0.0, 1e-12);
    EXPECT_EQ(loaded.allowedCollisions, problem.scene.allowedCollisions);
  }
}

}  // namespace
}  // namespace arcplan::benchmarks
