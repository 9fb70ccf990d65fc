// Floor grids of the self pairs two joints alone move against each other (collision/src/pair_floor_grid.h), on
// MotionBenchMaker's UR5 + Robotiq: every floor below FCL's distance of the pair anywhere in its cell, every motion a
// grid certifies keeping the distance at every dense state, one grid for every model of the robot.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/robot/kinematics.h"
#include "model_implementation.h"  // collision/src
#include "pair_floor_grid.h"       // collision/src
#include "support/collision_options.h"
#include "support/command.h"
#include "support/random_joint_state.h"

namespace {

using namespace arcplan::collision;
namespace fs = std::filesystem;

Scene mbmScene(const std::string& family, const std::string& number) {
  const fs::path mbm = arcplan::testing::sharedDataDirectory() / "mbm_ur5";
  const fs::path folder = mbm / "problems" / family;
  const MoveItRobot robot{mbm / "ur5.urdf", mbm / "ur5.srdf"};
  return loadMoveItProblem(folder / ("scene" + number + ".yaml"), folder / ("request" + number + ".yaml"), robot).scene;
}

std::string pairName(const CollisionModel& model, const detail::ModelImplementation::PairGroup& group) {
  return model.linkNames()[group.firstBody] + "–" + model.linkNames()[group.secondBody];
}

// FCL's distance of the group's bodies at q (the exact model's parts: meshes, GJK on convex parts).
double groupDistance(const CollisionModel& exact, const detail::ModelImplementation::PairGroup& group,
                     const Eigen::VectorXd& q) {
  const auto& impl = detail::implementationOf(exact);
  arcplan::robot::KinematicsData kinematics(exact.robot());
  arcplan::robot::forwardKinematics(exact.robot(), q, kinematics);
  double nearest = INFINITY;
  for (const auto& [i, j] : group.parts) {
    const Eigen::Isometry3d first = kinematics.linkPoses[impl.robotPartLink[i]] * impl.robotParts[i].offset;
    const Eigen::Isometry3d second = kinematics.linkPoses[impl.robotPartLink[j]] * impl.robotParts[j].offset;
    nearest = std::min(
        nearest, detail::partsDistance(impl.robotParts[i], first, impl.robotParts[j], second, true, exact.options()));
  }
  return nearest;
}

struct Ur5 {
  Scene scene = mbmScene("bookshelf_small_ur5", "0001");
  std::shared_ptr<const CollisionModel> layered = makeCollisionModel(scene);
  std::shared_ptr<const CollisionModel> exact = makeCollisionModel(scene, arcplan::testing::exactOnly());
  const detail::ModelImplementation& impl = detail::implementationOf(*layered);
  const detail::ModelImplementation& exactImpl = detail::implementationOf(*exact);
  std::vector<Eigen::Vector3d> axes = std::vector<Eigen::Vector3d>(impl.partPairs.size(), Eigen::Vector3d::Zero());

  // The groups with a grid, each with the exact model's group of the same bodies.
  std::vector<std::pair<const detail::ModelImplementation::PairGroup*, const detail::ModelImplementation::PairGroup*>>
  gridded() const {
    std::vector<std::pair<const detail::ModelImplementation::PairGroup*, const detail::ModelImplementation::PairGroup*>>
        pairs;
    for (const auto& group : impl.selfGroups) {
      if (!group.floorGrid) continue;
      for (const auto& other : exactImpl.selfGroups)
        if (other.firstBody == group.firstBody && other.secondBody == group.secondBody)
          pairs.emplace_back(&group, &other);
    }
    return pairs;
  }
};

// The UR5's pairs two joints apart get grids on exactly those joints; pairs one joint apart have a constant floor
// (or are allowed), pairs three or more apart have neither.
TEST(PairFloorGrid, PairsTwoJointsApartHaveGridsOnThoseJoints) {
  Ur5 ur5;
  int grids = 0;
  for (const auto& group : ur5.impl.selfGroups) {
    std::vector<int> moving;
    for (int j = 0; j < group.relativeReach.size(); ++j)
      if (group.relativeReach[j] > 0.0) moving.push_back(j);
    SCOPED_TRACE(pairName(*ur5.layered, group));
    if (group.rigid || moving.size() != 2) {
      EXPECT_FALSE(group.floorGrid);
      continue;
    }
    ASSERT_TRUE(group.floorGrid);
    EXPECT_EQ(group.floorGrid->jointA(), moving[0]);
    EXPECT_EQ(group.floorGrid->jointB(), moving[1]);
    ++grids;
  }
  // base_link–upper_arm_link, shoulder_link–forearm_link, upper_arm_link–wrist_1_link, forearm_link–wrist_2_link,
  // wrist_1_link–fts_robotside (docs/collision.md).
  EXPECT_EQ(grids, 5);
}

// 300 random states per pair, angles anywhere in (−2π, 2π), half of them at cells' corners: each floor is below FCL's
// distance of its pair, and the two pairs always within 1.8 cm get floors that keep a self pair's clearance at most
// states (the grid is of use).
TEST(PairFloorGrid, FloorsAreBelowFclsDistance) {
  Ur5 ur5;
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> angle(-2.0 * M_PI, 2.0 * M_PI);
  const double kept = 1.26e-3;  // keptClearance of a 1 mm self clearance
  for (const auto& [group, exactGroup] : ur5.gridded()) {
    SCOPED_TRACE(pairName(*ur5.layered, *group));
    int useful = 0, states = 0;
    for (int k = 0; k < 300; ++k) {
      Eigen::VectorXd q = arcplan::testing::randomJointState(ur5.layered->robot(), random);
      q[group->floorGrid->jointA()] = angle(random);
      q[group->floorGrid->jointB()] = angle(random);
      if (k % 2 == 0) {  // a cell's corner: the farthest from the centre its floor was measured at
        const double stepA = group->floorGrid->stepA(), stepB = group->floorGrid->stepB();
        q[group->floorGrid->jointA()] = -M_PI + std::round((q[group->floorGrid->jointA()] + M_PI) / stepA) * stepA;
        q[group->floorGrid->jointB()] = -M_PI + std::round((q[group->floorGrid->jointB()] + M_PI) / stepB) * stepB;
      }
      const double floor = group->floorGrid->at(q, ur5.axes.data());
      const double distance = groupDistance(*ur5.exact, *exactGroup, q);
      ASSERT_LE(floor, distance) << "state " << k;
      ++states;
      useful += distance < 0.018 && floor > kept;
    }
    const std::string name = pairName(*ur5.layered, *group);
    if (name == "forearm_link–wrist_2_link" || name == "base_link–upper_arm_link") {
      EXPECT_GT(useful, states * 3 / 4);
    }
  }
}

// Motions of up to 6 rad in the two joints (across ±π too) of the two pairs always within 1.8 cm: every one a grid says
// keeps 1.26 mm does so at 100 states along it (FCL), and many are certified (14 and 20 of 30 when written).
TEST(PairFloorGrid, MotionsAGridCertifiesKeepTheDistanceAtEveryState) {
  Ur5 ur5;
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> angle(-2.0 * M_PI, 2.0 * M_PI), change(-3.0, 3.0);
  const double kept = 1.26e-3;
  for (const auto& [group, exactGroup] : ur5.gridded()) {
    const std::string name = pairName(*ur5.layered, *group);
    if (name != "forearm_link–wrist_2_link" && name != "base_link–upper_arm_link") continue;
    SCOPED_TRACE(name);
    const int a = group->floorGrid->jointA(), b = group->floorGrid->jointB();
    int certified = 0;
    for (int k = 0; k < 30; ++k) {
      Eigen::VectorXd from = arcplan::testing::randomJointState(ur5.layered->robot(), random);
      from[a] = angle(random);
      from[b] = angle(random);
      Eigen::VectorXd to = from;
      to[a] += change(random);
      to[b] += change(random);
      if (!group->floorGrid->keepsAlong(from, to, kept, ur5.axes.data())) continue;
      ++certified;
      for (int s = 0; s <= 100; ++s) {
        const Eigen::VectorXd q = from + (s / 100.0) * (to - from);
        ASSERT_GT(groupDistance(*ur5.exact, *exactGroup, q), kept) << "motion " << k << " at " << s / 100.0;
      }
    }
    EXPECT_GT(certified, 10);
  }
}

// An angle that is not finite, or too large for a cell index, gets no floor (the query measures the pair as before).
TEST(PairFloorGrid, AnglesWithoutACellGetNoFloor) {
  Ur5 ur5;
  for (const auto& [group, exactGroup] : ur5.gridded()) {
    for (const double angle : {double(NAN), double(INFINITY), 1e300, -1e7}) {
      Eigen::VectorXd q = Eigen::VectorXd::Zero(ur5.layered->robot().dof());
      q[group->floorGrid->jointB()] = angle;
      EXPECT_EQ(group->floorGrid->at(q, ur5.axes.data()), -INFINITY) << angle;
      EXPECT_FALSE(group->floorGrid->keepsAlong(Eigen::VectorXd::Zero(q.size()), q, 0.0, ur5.axes.data())) << angle;
    }
  }
}

// A second model of the robot (another scene) shares the grids, with the cells the first measured.
TEST(PairFloorGrid, ModelsOfOneRobotShareTheirGrids) {
  Ur5 ur5;
  const auto other = makeCollisionModel(mbmScene("box_ur5", "0001"));
  const auto& otherImpl = detail::implementationOf(*other);
  for (const auto& [group, exactGroup] : ur5.gridded()) {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(ur5.layered->robot().dof());
    group->floorGrid->at(q, ur5.axes.data());
    int shared = 0;
    for (const auto& otherGroup : otherImpl.selfGroups)
      if (otherGroup.firstBody == group->firstBody && otherGroup.secondBody == group->secondBody)
        shared += otherGroup.floorGrid == group->floorGrid;
    EXPECT_EQ(shared, 1) << pairName(*ur5.layered, *group);
    EXPECT_GE(group->floorGrid->measuredCells(), 1);
  }
}

}  // namespace
