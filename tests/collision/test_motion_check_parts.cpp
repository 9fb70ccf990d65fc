// The pieces of the certified motion check added for MotionBenchMaker's long RRTConnect edges
// (docs/collision.md, "Motion checks" and "Layers"), each against an independent computation here:
// per-part-pair motion bounds against the measured displacement of every hull point, coarse containing
// hulls against their points, and long certified motions against exact states sampled along them.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <random>

#include <gtest/gtest.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/kinematics.h"
#include "convex_hull.h"           // collision/src
#include "model_implementation.h"  // collision/src
#include "support/command.h"
#include "support/joint_states.h"

namespace {

using namespace arcplan::collision;
namespace fs = std::filesystem;

// The thesis scene and bookshelf_small 0026 of MBM (where the shared data is).
std::vector<Scene> testScenes() {
  std::vector<Scene> scenes{loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml")};
  const fs::path mbm = arcplan::testing::sharedDataDirectory() / "mbm_ur5";
  const fs::path folder = mbm / "problems" / "bookshelf_small_ur5";
  if (fs::exists(folder)) {
    scenes.push_back(loadMoveItProblem(folder / "scene0026.yaml", folder / "request0026.yaml",
                                       MoveItRobot{mbm / "ur5.urdf", mbm / "ur5.srdf"})
                         .scene);
  }
  return scenes;
}

int commonAncestor(const arcplan::robot::RobotModel& robot, int a, int b) {
  for (int x = a; x >= 0; x = robot.links()[x].parent) {
    for (int y = b; y >= 0; y = robot.links()[y].parent) {
      if (x == y) return x;
    }
  }
  return -1;
}

TEST(CoarseHull, ContainsEveryPointOfASphereWithFewVertices) {
  // 5000 points on the unit sphere (seeded): the coarse hull keeps at most one vertex per direction,
  // contains every point, and stays close to the sphere (64 directions are ~26° apart, so its faces lie
  // within about 1/cos(13°) ≈ 1.03 of the centre; 1.25 leaves room for the scaling).
  std::mt19937_64 random(3);
  std::normal_distribution<double> gaussian;
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < 5000; ++k)
    points.push_back(Eigen::Vector3d(gaussian(random), gaussian(random), gaussian(random)).normalized());
  const auto coarse = detail::coarseContainingHull(points, 64);
  ASSERT_TRUE(coarse);
  EXPECT_LE(coarse->getVertices().size(), 64u);
  EXPECT_GE(coarse->getVertices().size(), 20u);
  EXPECT_LE(detail::largestOutside(*coarse, points), 0.0);
  for (const auto& v : coarse->getVertices()) EXPECT_LT(v.norm(), 1.25);
  EXPECT_FALSE(detail::coarseContainingHull({points[0], points[1], points[2]}, 64));  // no volume
}

TEST(CoarseHull, EveryCoarseHullOfTheMbmRobotContainsItsPart) {
  const auto scenes = testScenes();
  for (const Scene& scene : scenes) {
    const auto model = makeCollisionModel(scene);
    int coarse = 0;
    for (const auto& part : detail::implementationOf(*model).robotParts) {
      if (!part.coarseHullGeometry) continue;
      const auto& hull = static_cast<const fcl::Convexd&>(*part.hullGeometry);
      const auto& shape = static_cast<const fcl::Convexd&>(*part.coarseHullGeometry);
      EXPECT_LE(detail::largestOutside(shape, part.hullPoints), 0.0) << model->linkNames()[part.body];
      EXPECT_LT(shape.getVertices().size(), hull.getVertices().size());
      ++coarse;
    }
    // The UR10e's parts are convex (no hulls of their own); the FTS300 and Robotiq meshes get coarse hulls.
    if (scene.robot.isBuiltIn()) {
      EXPECT_EQ(coarse, 0);
    } else {
      EXPECT_GE(coarse, 5);
    }
  }
}

// ModelImplementation::partPairReach: on a straight joint motion, in the frame of the two bodies'
// nearest common ancestor (the world for obstacles), the points of both parts together move no
// farther than partPairReach · |Δq|; and on the MBM arm it is much tighter than the group's bound for
// some part pairs (parts near a joint axis).
TEST(MotionBoundsPerPart, NoHullPointMovesFartherThanItsPartPairBound) {
  for (const Scene& scene : testScenes()) {
    const auto model = makeCollisionModel(scene);
    const auto& impl = detail::implementationOf(*model);
    const auto& robot = model->robot();
    arcplan::robot::KinematicsData from(robot), to(robot);
    std::mt19937_64 random(29);
    double tightest = 1.0;  // smallest part-pair bound / group bound seen
    for (int trial = 0; trial < 12; ++trial) {
      const Eigen::VectorXd qa = arcplan::testing::randomJointState(robot, random);
      Eigen::VectorXd dq(robot.dof());
      const double scale = trial % 2 == 0 ? 1.5 : 0.05;
      for (int j = 0; j < dq.size(); ++j) dq[j] = std::uniform_real_distribution<double>(-scale, scale)(random);
      const Eigen::VectorXd qb = qa + dq;
      arcplan::robot::forwardKinematics(robot, qa, from);
      arcplan::robot::forwardKinematics(robot, qb, to);
      // Largest displacement of part i's points in the frame of link `frame` (-1: the world).
      std::map<std::pair<int, int>, double> moved;
      const auto displacement = [&](int i, int frame) {
        const auto key = std::pair{i, frame};
        if (const auto found = moved.find(key); found != moved.end()) return found->second;
        const int link = impl.robotPartLink[i];
        const Eigen::Isometry3d a =
            (frame < 0 ? Eigen::Isometry3d::Identity() : from.linkPoses[frame].inverse()) * from.linkPoses[link];
        const Eigen::Isometry3d b =
            (frame < 0 ? Eigen::Isometry3d::Identity() : to.linkPoses[frame].inverse()) * to.linkPoses[link];
        const auto& part = impl.robotParts[i];
        double farthest = 0.0;
        for (const auto& v : part.hullPoints)
          farthest = std::max(farthest, (b * (part.offset * v) - a * (part.offset * v)).norm());
        return moved[key] = farthest;
      };
      for (std::size_t p = 0; p < impl.partPairs.size(); ++p) {
        const auto& [group, i, j] = impl.partPairs[p];
        if (impl.robotParts[i].hullPoints.empty()) continue;  // spheres and cylinders: no points to follow
        const double bound = impl.partPairReach.row(static_cast<Eigen::Index>(p)).dot(dq.cwiseAbs());
        double measured = 0.0;
        if (group->self) {
          if (impl.robotParts[j].hullPoints.empty()) continue;
          const int frame =
              commonAncestor(robot, impl.linkCapsuleLink[group->firstBody], impl.linkCapsuleLink[group->secondBody]);
          measured = displacement(i, frame) + displacement(j, frame);
        } else {
          measured = displacement(i, -1);
        }
        ASSERT_LE(measured, bound + 1e-12) << model->linkNames()[group->firstBody] << " part pair " << p;
        const double groupBound = group->relativeReach.dot(dq.cwiseAbs());
        ASSERT_LE(bound, groupBound + 1e-12);  // a part is part of its body
        if (groupBound > 0.0) tightest = std::min(tightest, bound / groupBound);
      }
    }
    if (!scene.robot.isBuiltIn()) {
      EXPECT_LT(tightest, 0.5);
    }
  }
}

// Long motions (0.5–3 rad, as RRTConnect's edges on MBM) at 1 cm: an accepted motion has no colliding
// state among 601 exact states along it (FCL on the meshes only) and keeps 1 cm (less the exact
// distances' 1e-6 m) at each, by the state check hasClearance (its own tests compare it with FCL; FCL
// distances at every state took 100-140 s instead of 3 s); both answers occur.
TEST(CertifiedMotionCheck, LongMbmMotionsAcceptedKeepMinimumClearanceAtEveryExactSample) {
  CollisionModelOptions exactOnly;
  exactOnly.spherePrefilter = false;
  exactOnly.hullLayer = false;
  for (const Scene& scene : testScenes()) {
    const auto model = makeCollisionModel(scene), exact = makeCollisionModel(scene, exactOnly);
    CollisionData data(*model), exactData(*exact);
    std::mt19937_64 random(41);
    MotionCheckOptions options;
    options.minimumClearance = 0.01;
    int accepted = 0, rejected = 0;
    while (accepted + rejected < 40) {
      const Eigen::VectorXd start = arcplan::testing::randomJointState(model->robot(), random);
      if (!hasClearance(*model, data, start, options.minimumClearance)) continue;
      const Eigen::VectorXd end = arcplan::testing::randomJointState(model->robot(), random);
      if (!hasClearance(*model, data, end, options.minimumClearance)) continue;
      if (!isMotionCollisionFree(*model, data, start, end, nullptr, options)) {
        ++rejected;
        continue;
      }
      ++accepted;
      for (int k = 0; k <= 600; ++k) {
        const Eigen::VectorXd q = start + (k / 600.0) * (end - start);
        ASSERT_TRUE(isCollisionFree(*exact, exactData, q)) << scene.name << " " << k;
        ASSERT_TRUE(hasClearance(*model, data, q, options.minimumClearance - 1e-6)) << scene.name << " " << k;
      }
    }
    EXPECT_GT(accepted, 0) << scene.name;
    EXPECT_GT(rejected, 0) << scene.name;
  }
}

// A motion of an RRTConnect path on MBM bookshelf_thin 0081 (1 cm, seed 18, simplified) that the
// certified check accepted at minimumClearance 1 cm while passing 9.8 mm from the scene: certificates
// ran to contact, not to minimumClearance, so between measurements a motion could pass closer than it.
// They now keep minimumClearance; the expected answer is from 501 exact distances along the motion.
TEST(CertifiedMotionCheck, AnAcceptedMotionKeepsMinimumClearanceBetweenMeasurements) {
  const fs::path mbm = arcplan::testing::sharedDataDirectory() / "mbm_ur5";
  const fs::path folder = mbm / "problems" / "bookshelf_thin_ur5";
  ASSERT_TRUE(fs::exists(folder)) << folder;
  const Scene scene = loadMoveItProblem(folder / "scene0081.yaml", folder / "request0081.yaml",
                                        MoveItRobot{mbm / "ur5.urdf", mbm / "ur5.srdf"})
                          .scene;
  const auto model = makeCollisionModel(scene);
  CollisionData data(*model);
  Eigen::VectorXd from(6), to(6);
  from << -0.18017124096981552, 0.078777815922644046, 1.3810103026807332, 0.75038577636865655, 1.2522888875915212,
      0.87925248731431083;
  to << -0.062075343504580285, 0.059427600899704933, 1.8268016368820166, 1.1939555137563569, 1.3898775106760048,
      1.2447343093261072;
  double closest = 1.0;
  for (int k = 0; k <= 500; ++k)
    closest = std::min(closest, distance(*model, data, from + (k / 500.0) * (to - from)).minimum());
  ASSERT_LT(closest, 0.0099);
  ASSERT_GT(closest, 0.009);
  ASSERT_GT(distance(*model, data, from).minimum(), 0.01);
  ASSERT_GT(distance(*model, data, to).minimum(), 0.01);
  MotionCheckOptions options;
  options.minimumClearance = 0.01;
  EXPECT_FALSE(isMotionCollisionFree(*model, data, from, to, nullptr, options));
  EXPECT_FALSE(isMotionCollisionFree(*model, data, to, from, nullptr, options));
  // At 8 mm (1.8 mm below what it keeps, more than the 0.5 mm margin) it is accepted.
  options.minimumClearance = 0.008;
  EXPECT_TRUE(isMotionCollisionFree(*model, data, from, to, nullptr, options));
}

}  // namespace
