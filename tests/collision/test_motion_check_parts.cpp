// The pieces of the certified motion check added for MotionBenchMaker's long RRTConnect edges
// (docs/collision.md, "Motion checks" and "Layers"), each against an independent computation here:
// per-part-pair motion bounds against the measured displacement of every hull point (seen from either part), coarse
// containing hulls against their points, and long certified motions against exact states sampled along them.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <tuple>

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

// ModelImplementation::partPairReach bounds how fast two parts' distance can change. An obstacle part
// stays put: the robot part's points move no farther (in the world) than partPairReach · |Δq|. Two robot
// parts: the motion is taken one joint at a time (qa, then joint 0 changed, then joint 1 too, ...); a
// step changes their distance by at most how far the points of one move in the other's link frame (the
// same relative motion seen from either part), and the sum over the steps of the smaller of the two is
// at most partPairReach · |Δq|. On the MBM arm the bound is much tighter than the group's for some part
// pairs (parts near a joint axis), and below the moving part's own displacement for some (the base seen
// from the upper arm's end cap, motion_bounds.cpp fixedSideReach).
// A body's reach for joint j bounds the distance of its points from j's axis in every configuration
// (motion_bounds.cpp axisReach): measured here with forward kinematics on random configurations, every hull
// point of every part against every joint that moves it. For the joint of the body's own link the reach is
// that distance itself (the points turn about the axis rigidly), so the samples come within 1 % of it.
TEST(MotionBounds, NoPointIsFartherFromAJointsAxisThanItsReach) {
  for (const Scene& scene : testScenes()) {
    const auto model = makeCollisionModel(scene);
    const auto& impl = detail::implementationOf(*model);
    const auto& robot = model->robot();
    arcplan::robot::KinematicsData kinematics(robot);
    std::mt19937_64 random(29);
    const auto bodies = static_cast<Eigen::Index>(model->linkNames().size());
    Eigen::MatrixXd farthest = Eigen::MatrixXd::Zero(bodies, robot.dof());
    for (int trial = 0; trial < 600; ++trial) {
      arcplan::robot::forwardKinematics(robot, arcplan::testing::randomJointState(robot, random), kinematics);
      for (const auto& part : impl.robotParts) {
        const int link = impl.linkCapsuleLink[static_cast<std::size_t>(part.body)];
        for (int l = link; l >= 0; l = robot.links()[l].parent) {
          const int joint = robot.links()[l].joint;
          if (joint < 0) continue;
          const Eigen::Vector3d origin = kinematics.linkPoses[l].translation();
          const Eigen::Vector3d axis = kinematics.linkPoses[l].linear() * robot.links()[l].axis;
          for (const Eigen::Vector3d& point : part.hullPoints) {
            const Eigen::Vector3d p = kinematics.linkPoses[link] * (part.offset * point) - origin;
            double& d = farthest(part.body, joint);
            d = std::max(d, (p - p.dot(axis) * axis).norm());
          }
        }
      }
    }
    for (Eigen::Index b = 0; b < bodies; ++b) {
      for (int j = 0; j < robot.dof(); ++j) {
        EXPECT_LE(farthest(b, j), impl.jointReach(b, j) + 1e-9) << model->linkNames()[b] << " joint " << j;
      }
    }
    for (const auto& part : impl.robotParts) {
      const int joint = robot.links()[impl.linkCapsuleLink[static_cast<std::size_t>(part.body)]].joint;
      if (joint >= 0 && !part.hullPoints.empty()) {
        EXPECT_GT(farthest(part.body, joint), 0.99 * impl.jointReach(part.body, joint))
            << model->linkNames()[part.body];
      }
    }
  }
}

TEST(MotionBoundsPerPart, NoPartPairMovesFartherThanItsBound) {
  for (const Scene& scene : testScenes()) {
    const auto model = makeCollisionModel(scene);
    const auto& impl = detail::implementationOf(*model);
    const auto& robot = model->robot();
    const int dof = robot.dof();
    std::vector<arcplan::robot::KinematicsData> steps(static_cast<std::size_t>(dof) + 1,
                                                      arcplan::robot::KinematicsData(robot));
    std::mt19937_64 random(29);
    double tightest = 1.0;  // smallest part-pair bound / group bound seen
    int fromStillSide = 0;  // part pairs bounded below the displacement of the part that moves
    for (int trial = 0; trial < 12; ++trial) {
      const Eigen::VectorXd qa = arcplan::testing::randomJointState(robot, random);
      Eigen::VectorXd dq(dof), q = qa;
      const double scale = trial % 2 == 0 ? 1.5 : 0.05;
      for (int j = 0; j < dof; ++j) dq[j] = std::uniform_real_distribution<double>(-scale, scale)(random);
      arcplan::robot::forwardKinematics(robot, q, steps[0]);
      for (int j = 0; j < dof; ++j) {
        q[j] += dq[j];
        arcplan::robot::forwardKinematics(robot, q, steps[static_cast<std::size_t>(j) + 1]);
      }
      // Largest displacement of part i's points in the frame of link `frame` (-1: the world) from step
      // `from` to step `to`.
      std::map<std::tuple<int, int, int, int>, double> moved;
      const auto displacement = [&](int i, int frame, int from, int to) {
        const auto key = std::tuple{i, frame, from, to};
        if (const auto found = moved.find(key); found != moved.end()) return found->second;
        const auto pose = [&](int k) {
          const auto& links = steps[static_cast<std::size_t>(k)].linkPoses;
          return (frame < 0 ? Eigen::Isometry3d::Identity() : links[frame].inverse()) * links[impl.robotPartLink[i]];
        };
        const Eigen::Isometry3d a = pose(from), b = pose(to);
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
          const int linkI = impl.robotPartLink[i], linkJ = impl.robotPartLink[j];
          for (int k = 0; k < dof; ++k) {
            const double seenFromJ = displacement(i, linkJ, k, k + 1), seenFromI = displacement(j, linkI, k, k + 1);
            measured += std::min(seenFromJ, seenFromI);
          }
          // The moving part's own displacement where the pair does not share it (their nearest common ancestor).
          const int frame = commonAncestor(robot, linkI, linkJ);
          if (displacement(i, frame, 0, dof) + displacement(j, frame, 0, dof) > bound + 1e-9) ++fromStillSide;
        } else {
          measured = displacement(i, -1, 0, dof);
        }
        ASSERT_LE(measured, bound + 1e-12) << model->linkNames()[group->firstBody] << " part pair " << p;
        const double groupBound = group->relativeReach.dot(dq.cwiseAbs());
        ASSERT_LE(bound, groupBound + 1e-12);  // a part is part of its body
        if (groupBound > 0.0) tightest = std::min(tightest, bound / groupBound);
      }
    }
    if (!scene.robot.isBuiltIn()) {
      EXPECT_LT(tightest, 0.5);
      EXPECT_GT(fromStillSide, 0);
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
// They now keep each pair's own m (LongMbmMotionsAcceptedKeepMinimumClearanceAtEveryExactSample checks that
// at every exact sample of accepted motions). The 9.8 mm were between forearm_link and wrist_2_link, a self pair,
// which keeps only min(m, 1 mm) (collision_model.h): at 1 cm the motion is accepted, as it is at 8 mm; its
// obstacles stay more than 30 cm away. Expected answers from 501 exact distances along the motion.
TEST(CertifiedMotionCheck, AnAcceptedMotionKeepsEachPairsOwnMinimumClearance) {
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
  double obstacles = 1.0, self = 1.0;
  for (int k = 0; k <= 500; ++k) {
    const DistanceReport report = distance(*model, data, from + (k / 500.0) * (to - from));
    obstacles = std::min(obstacles, report.obstacleDistance);
    self = std::min(self, report.selfDistance);
  }
  ASSERT_GT(obstacles, 0.3);
  ASSERT_LT(self, 0.0099);
  ASSERT_GT(self, 0.009);  // far above the 1 mm (+ 0.25 mm margin) the self pair keeps at any clearance
  MotionCheckOptions options;
  options.minimumClearance = 0.01;
  EXPECT_TRUE(isMotionCollisionFree(*model, data, from, to, nullptr, options));
  EXPECT_TRUE(isMotionCollisionFree(*model, data, to, from, nullptr, options));
  options.minimumClearance = 0.008;
  EXPECT_TRUE(isMotionCollisionFree(*model, data, from, to, nullptr, options));
  // Above the obstacles' distance along it the motion is refused: the clearance still holds from the scene.
  options.minimumClearance = obstacles + 0.001;
  EXPECT_FALSE(isMotionCollisionFree(*model, data, from, to, nullptr, options));
}

}  // namespace
