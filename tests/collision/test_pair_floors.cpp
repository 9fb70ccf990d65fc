// Floors of the self pairs one joint alone moves against each other (collision/src/pair_floors.cpp,
// docs/collision.md "Layers"): checked against exact FCL distances of the pair's meshes, sampled here
// densely over that joint with the other joints random.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/moveit_scene.h"
#include "model_implementation.h"  // collision/src
#include "support/command.h"
#include "support/random_joint_state.h"

namespace {

using namespace arcplan::collision;
namespace fs = std::filesystem;

Scene mbmScene() {
  const fs::path mbm = arcplan::testing::sharedDataDirectory() / "mbm_ur5";
  const fs::path folder = mbm / "problems" / "bookshelf_small_ur5";
  return loadMoveItProblem(folder / "scene0026.yaml", folder / "request0026.yaml",
                           MoveItRobot{mbm / "ur5.urdf", mbm / "ur5.srdf"})
      .scene;
}

// The exact distance of a self group's bodies in the current configuration: FCL on every part pair.
double exactGroupDistance(const CollisionModel& model, detail::Workspace& data,
                          const detail::ModelImplementation::PairGroup& group) {
  const auto& impl = detail::implementationOf(model);
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& [i, j] : group.parts) {
    detail::ensurePart(impl, data, i);
    detail::ensurePart(impl, data, j);
    nearest = std::min(nearest, detail::partsDistance(impl.robotParts[i], data.partPoses[i], impl.robotParts[j],
                                                      data.partPoses[j], true, model.options()));
  }
  return nearest;
}

TEST(PairFloors, OneJointPairsOfTheMbmRobotKeepTheirFloorEverywhere) {
  const Scene scene = mbmScene();
  const auto layered = makeCollisionModel(scene);
  CollisionModelOptions exactOptions;
  exactOptions.spherePrefilter = false;
  exactOptions.hullLayer = false;
  const auto exact = makeCollisionModel(scene, exactOptions);
  CollisionData exactData(*exact);
  detail::Workspace& data = detail::workspaceOf(exactData);
  const auto& impl = detail::implementationOf(*layered);
  const auto& exactGroups = detail::implementationOf(*exact).selfGroups;
  ASSERT_EQ(impl.selfGroups.size(), exactGroups.size());
  std::mt19937_64 random(11);
  int floored = 0;
  bool sensor = false;
  for (std::size_t g = 0; g < impl.selfGroups.size(); ++g) {
    const auto& group = impl.selfGroups[g];
    if (!(group.floor > 0.0)) continue;
    ++floored;
    const std::string first = layered->linkNames()[group.firstBody], second = layered->linkNames()[group.secondBody];
    sensor = sensor || (first == "wrist_2_link" && second == "fts_robotside");
    int joint = -1, moving = 0;
    for (int j = 0; j < group.relativeReach.size(); ++j) {
      if (group.relativeReach[j] > 0.0) {
        joint = j;
        ++moving;
      }
    }
    ASSERT_EQ(moving, 1) << first << " - " << second;
    // 360 angles over one whole turn (queries may ask angles outside the limits), the other joints random: the
    // pair's distance depends on that joint alone, so this samples all of it.
    double smallest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 360; ++k) {
      Eigen::VectorXd q = arcplan::testing::randomJointState(layered->robot(), random);
      q[joint] = -M_PI + 2.0 * M_PI * k / 359.0;
      detail::updateRobot(*exact, data, q);
      const double d = exactGroupDistance(*exact, data, exactGroups[g]);
      EXPECT_GE(d, group.floor) << first << " - " << second << " at q" << joint << " = " << q[joint];
      smallest = std::min(smallest, d);
    }
    // Not vacuous: within 1 mm of the smallest sampled distance (cells lose at most 0.5 mm, the hulls the rest).
    EXPECT_GT(group.floor, smallest - 0.001) << first << " - " << second;
  }
  EXPECT_TRUE(sensor) << "wrist_2_link - fts_robotside has no floor";
  EXPECT_GE(floored, 1);
}

// The floor's purpose: queries answer as FCL alone does, with the pair left unmeasured where its floor
// answers. Every other self pair allowed and the obstacles removed, so the sensor pair (2.8 cm apart) is
// the robot's nearest pair: the per-kind query under hasClearance asking below, at and above its floor of the
// pair, and distance(), against FCL alone. hasClearance itself asks at most 1 mm of a self pair
// (collision_model.h), which the floor answers at every clearance.
TEST(PairFloors, QueriesAnswerAsFclWhereTheFloorDecides) {
  Scene scene = mbmScene();
  scene.obstacles.clear();
  const auto full = makeCollisionModel(scene);
  for (const auto& group : detail::implementationOf(*full).selfGroups) {
    const std::string first = full->linkNames()[group.firstBody], second = full->linkNames()[group.secondBody];
    if (!(first == "wrist_2_link" && second == "fts_robotside")) scene.allowedCollisions.emplace_back(first, second);
  }
  const auto layered = makeCollisionModel(scene);
  ASSERT_EQ(detail::implementationOf(*layered).selfGroups.size(), 1u);
  const double floor = detail::implementationOf(*layered).selfGroups[0].floor;
  ASSERT_GT(floor, 0.02);
  CollisionModelOptions exactOptions;
  exactOptions.spherePrefilter = false;
  exactOptions.hullLayer = false;
  const auto exact = makeCollisionModel(scene, exactOptions);
  CollisionData layeredData(*layered), exactData(*exact);
  detail::Workspace& exactWorkspace = detail::workspaceOf(exactData);
  const auto& exactGroup = detail::implementationOf(*exact).selfGroups.at(0);
  std::mt19937_64 random(12);
  int clear[3] = {0, 0, 0};
  const double clearances[3] = {floor - 0.001, floor, 0.03};
  for (int k = 0; k < 200; ++k) {
    const Eigen::VectorXd q = arcplan::testing::randomJointState(layered->robot(), random);
    // FCL on every part pair of the group, not the queries under test (which use the floor).
    detail::updateRobot(*exact, exactWorkspace, q);
    const double expected = exactGroupDistance(*exact, exactWorkspace, exactGroup);
    EXPECT_NEAR(distance(*layered, layeredData, q).minimum(), expected, 1e-9) << "state " << k;
    EXPECT_TRUE(isCollisionFree(*layered, layeredData, q));
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(detail::keepsDistances(*layered, layeredData, q, clearances[c], clearances[c]),
                expected >= clearances[c])
          << "state " << k;
      EXPECT_EQ(hasClearance(*layered, layeredData, q, clearances[c]), expected >= 0.001) << "state " << k;
      clear[c] += expected >= clearances[c];
    }
  }
  EXPECT_EQ(clear[0], 200);
  EXPECT_EQ(clear[2], 0);  // the pair is never 3 cm apart: the floor does not answer those
}

// Floors are measured once per process and robot (pair_floors.cpp keeps them keyed by everything they
// depend on): a second model of the same robot takes the first one's, bit for bit; a model whose bounds
// differ (no hull layer: capsules only, a lower floor) measures its own instead of taking the layered one's.
TEST(PairFloors, AModelOfTheSameRobotTakesTheSameFloorsAndOtherBoundsTheirOwn) {
  const Scene scene = mbmScene();
  const auto first = makeCollisionModel(scene), second = makeCollisionModel(scene);
  CollisionModelOptions capsulesOnly;
  capsulesOnly.hullLayer = false;
  const auto capsules = makeCollisionModel(scene, capsulesOnly);
  const auto& groups = detail::implementationOf(*first).selfGroups;
  const auto& again = detail::implementationOf(*second).selfGroups;
  const auto& loose = detail::implementationOf(*capsules).selfGroups;
  ASSERT_EQ(groups.size(), again.size());
  ASSERT_EQ(groups.size(), loose.size());
  int floored = 0;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    EXPECT_EQ(groups[k].floor, again[k].floor) << first->linkNames()[groups[k].firstBody];
    if (groups[k].floor > 0.0) {
      ++floored;
      EXPECT_LT(loose[k].floor, groups[k].floor - 0.001) << "capsules bound the sensor pair far lower than hulls";
    }
  }
  EXPECT_GE(floored, 1);
}

}  // namespace
