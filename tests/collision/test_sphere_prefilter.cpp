// The sphere prefilter (collision/src/sphere_prefilter.h) against independent references: the
// spheres contain random points of every part's convex hull (not only the vertices the generator
// checks); the float kernels' gaps agree with the same gaps computed here in double from
// robot::forwardKinematics, within the error bound the margin is built on; the AVX2 and portable
// kernels and every batch composition give the same decisions; and every answer (states one by one,
// batches, certified motions) is FCL's, compared with a model built with the prefilter off, on the
// thesis scenes and seeded random scenes with boxes, cylinders, spheres and meshes.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "arcplan/collision/batch_check.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/primitive_mesh.h"
#include "model_implementation.h"  // collision/src
#include "sphere_prefilter.h"
#include "support/joint_states.h"

namespace {

using namespace arcplan::collision;
using Eigen::VectorXd;

Scene sceneFile(const char* name) { return loadScene(arcplan::dataDirectory() / "scenes" / name); }

// A seeded workcell: the table of the thesis and `count` obstacles of every kind in reach of the arm.
Scene randomScene(unsigned seed, int count) {
  Scene scene = sceneFile("thesis_free.yaml");
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < count; ++k) {
    Obstacle o;
    o.name = "random_" + std::to_string(k);
    const double radius = 0.02 + 0.12 * unit(random);
    switch (k % 4) {
      case 0:
        o.shape = Obstacle::Shape::Sphere;
        o.radius = radius;
        break;
      case 1:
        o.shape = Obstacle::Shape::Box;
        o.size = Eigen::Vector3d(0.05 + 0.3 * unit(random), 0.05 + 0.3 * unit(random), 0.05 + 0.3 * unit(random));
        break;
      case 2:
        o.shape = Obstacle::Shape::Cylinder;
        o.radius = radius;
        o.length = 0.05 + 0.4 * unit(random);
        break;
      default:
        o.shape = Obstacle::Shape::Mesh;
        o.meshData = std::make_shared<arcplan::robot::TriangleMesh>(
            arcplan::robot::cylinderMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.1, 0.2, 0.3), radius, 12));
    }
    const double angle = 2.0 * M_PI * unit(random), distance = 0.35 + 0.8 * unit(random);
    o.pose = Eigen::Translation3d(distance * std::cos(angle), distance * std::sin(angle), 0.1 + 0.9 * unit(random)) *
             Eigen::AngleAxisd(3.0 * unit(random), Eigen::Vector3d(unit(random), unit(random), 1.0).normalized());
    scene.obstacles.push_back(std::move(o));
  }
  return scene;
}

std::shared_ptr<const CollisionModel> modelOf(const Scene& scene, bool prefilter) {
  CollisionModelOptions options;
  options.spherePrefilter = prefilter;
  return makeCollisionModel(scene, options);
}

const detail::SpherePrefilter& prefilterOf(const CollisionModel& model) {
  return *detail::implementationOf(model).prefilter;
}

TEST(SphereModel, ContainsRandomPointsOfEveryPartsHull) {
  const auto model = modelOf(sceneFile("thesis_obstacle.yaml"), true);
  const auto& impl = detail::implementationOf(*model);
  const auto& spheres = prefilterOf(*model).spheres();
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  for (const auto& part : impl.robotParts) {
    const auto& body = spheres[static_cast<std::size_t>(part.body)];
    ASSERT_FALSE(part.hullPoints.empty());
    std::uniform_int_distribution<std::size_t> pick(0, part.hullPoints.size() - 1);
    for (int sample = 0; sample < 2000; ++sample) {
      // A point of the hull: a random convex combination of up to 4 vertices (edges, faces, inside).
      const int corners = 1 + sample % 4;
      Eigen::Vector3d point = Eigen::Vector3d::Zero();
      double total = 0.0;
      for (int c = 0; c < corners; ++c) {
        const double weight = unit(random);
        point += weight * part.hullPoints[pick(random)];
        total += weight;
      }
      const Eigen::Vector3d inLink = part.offset * (point / total);
      const bool inside = std::any_of(body.fine.begin(), body.fine.end(),
                                      [&](const detail::Sphere& s) { return (inLink - s.centre).norm() <= s.radius; });
      ASSERT_TRUE(inside) << "link " << model->linkNames()[part.body] << " point " << inLink.transpose();
      ASSERT_LE((inLink - body.coarse.centre).norm(), body.coarse.radius);
      const bool inGroup = std::any_of(body.groups.begin(), body.groups.end(), [&](const detail::SphereGroup& g) {
        return (inLink - g.bound.centre).norm() <= g.bound.radius;
      });
      ASSERT_TRUE(inGroup) << "link " << model->linkNames()[part.body] << " point " << inLink.transpose();
      ++checked;
    }
  }
  EXPECT_GT(checked, 10000);
  // The arm links are long enough to be cut into several groups, each a few neighbouring spheres.
  for (const auto& body : spheres) {
    int covered = 0;
    for (const auto& group : body.groups) {
      EXPECT_EQ(group.begin, covered);
      EXPECT_LE(group.count, 4);
      covered += group.count;
    }
    EXPECT_EQ(covered, static_cast<int>(body.fine.size()));
  }
  EXPECT_GE(std::count_if(spheres.begin(), spheres.end(), [](const auto& body) { return body.groups.size() >= 3; }), 2);
  // Within the kernels' fixed limit.
  std::size_t total = 0;
  for (const auto& body : spheres) total += body.fine.size();
  EXPECT_LE(total, static_cast<std::size_t>(detail::prefilter::kMaxFineSpheres));
  EXPECT_TRUE(prefilterOf(*model).usable());
}

// Distance from a point to the thesis obstacles' volumes, in double, written here.
double boxDistance(const Eigen::Vector3d& local, const Eigen::Vector3d& half) {
  return (local.cwiseAbs() - half).cwiseMax(0.0).norm();
}

// The smallest gap between body b's fine spheres, placed by `kinematics`, and its obstacles of the thesis scene
// (boxes and spheres), in double; infinite for a body checked against none.
double fineObstacleGap(const Scene& scene, const detail::ModelImplementation& impl, const detail::SphereModel& spheres,
                       const arcplan::robot::KinematicsData& kinematics, int b) {
  const auto& pose = kinematics.linkPoses[impl.linkCapsuleLink[b]];
  double gap = INFINITY;
  for (const auto& group : impl.obstacleGroups) {
    if (group.firstBody != b) continue;
    const Obstacle& obstacle = scene.obstacles[group.secondBody];
    for (const auto& s : spheres[b].fine) {
      const Eigen::Vector3d local = obstacle.pose.inverse() * (pose * s.centre);
      const double d = obstacle.shape == Obstacle::Shape::Box ? boxDistance(local, obstacle.size / 2.0)
                                                              : local.norm() - obstacle.radius;
      gap = std::min(gap, d - s.radius);
    }
  }
  return gap;
}

// kLanes seeded random states of the robot, loaded into the lanes of `work`.
std::vector<VectorXd> loadRandomBatch(const detail::SpherePrefilter& prefilter, detail::SphereWorkspace& work,
                                      const arcplan::robot::RobotModel& robot, std::mt19937_64& random) {
  std::vector<VectorXd> qs;
  for (int lane = 0; lane < detail::prefilter::kLanes; ++lane) {
    qs.push_back(arcplan::testing::randomJointState(robot, random));
    prefilter.loadLane(work, lane, qs.back().data());
  }
  return qs;
}

TEST(SpherePrefilter, FloatGapsAgreeWithDoubleWithinTheMargin) {
  const Scene scene = sceneFile("thesis_obstacle.yaml");
  const auto model = modelOf(scene, true);
  const auto& prefilter = prefilterOf(*model);
  const auto& impl = detail::implementationOf(*model);
  const auto& spheres = prefilter.spheres();
  detail::SphereWorkspace work;
  prefilter.prepare(work);
  std::fill(work.enough.begin(), work.enough.end(), 1e30f);  // fine spheres for every pair
  arcplan::robot::KinematicsData kinematics(model->robot());
  std::mt19937_64 random(9);
  double largestError = 0.0;
  for (int batch = 0; batch < 200; ++batch) {
    const std::vector<VectorXd> qs = loadRandomBatch(prefilter, work, model->robot(), random);
    prefilter.gaps(work);
    for (int lane = 0; lane < detail::prefilter::kLanes; ++lane) {
      arcplan::robot::forwardKinematics(model->robot(), qs[lane], kinematics);
      for (int b = 0; b < static_cast<int>(spheres.size()); ++b) {
        const double expected = fineObstacleGap(scene, impl, spheres, kinematics, b);
        if (!std::isfinite(expected)) continue;
        const double measured = work.gaps[b * detail::prefilter::kLanes + lane] + prefilter.margin();
        largestError = std::max(largestError, std::abs(measured - expected));
      }
    }
  }
  // The base (no joint moves it) has its one obstacle, the particle, measured once: not in the kernel's
  // tables, yet its gap above was the fine spheres' gap like every other body's.
  EXPECT_EQ(prefilter.tables().bodies[0].obstacleCount, 0);
  EXPECT_LT(prefilter.tables().bodies[0].fixedGap, 1.0f);
  // The margin is twice the derived bound: the measured error must stay below half of it.
  EXPECT_LT(largestError, prefilter.margin() / 2.0);
  EXPECT_GT(largestError, 0.0);         // float really differs from double: the comparison measured something
  EXPECT_LT(prefilter.margin(), 1e-3);  // and the margin stays small enough to clear most free states
}

// With a finite `enough` the kernels may stop at a coarse sphere or a group's ball: every gap must stay
// a lower bound of the fine spheres' distance (computed here in double, for obstacles and self pairs),
// and a pair whose gap falls below `enough` must have been measured with its fine spheres.
TEST(SpherePrefilter, GapsBelowTheirThresholdAreTheFineSpheresGaps) {
  const Scene scene = sceneFile("thesis_obstacle.yaml");
  const auto model = modelOf(scene, true);
  const auto& prefilter = prefilterOf(*model);
  const auto& impl = detail::implementationOf(*model);
  const auto& spheres = prefilter.spheres();
  const int bodies = static_cast<int>(spheres.size());
  detail::SphereWorkspace work;
  prefilter.prepare(work);
  arcplan::robot::KinematicsData kinematics(model->robot());
  std::mt19937_64 random(41);
  std::uniform_real_distribution<float> threshold(0.0f, 0.3f);
  const double tolerance = prefilter.margin() / 2.0;
  int below = 0, above = 0;
  for (int batch = 0; batch < 200; ++batch) {
    const std::vector<VectorXd> qs = loadRandomBatch(prefilter, work, model->robot(), random);
    for (auto& enough : work.enough) enough = threshold(random);
    prefilter.gaps(work);
    for (int lane = 0; lane < detail::prefilter::kLanes; ++lane) {
      arcplan::robot::forwardKinematics(model->robot(), qs[lane], kinematics);
      const auto world = [&](int b, const detail::Sphere& s) {
        return Eigen::Vector3d(kinematics.linkPoses[impl.linkCapsuleLink[b]] * s.centre);
      };
      std::vector<double> expected(static_cast<std::size_t>(prefilter.pairCount()), INFINITY);
      for (int b = 0; b < bodies; ++b) expected[b] = fineObstacleGap(scene, impl, spheres, kinematics, b);
      for (int p = 0; p < prefilter.tables().selfPairCount; ++p) {
        const int a = prefilter.tables().selfPairs[2 * p], b = prefilter.tables().selfPairs[2 * p + 1];
        for (const auto& sa : spheres[a].fine)
          for (const auto& sb : spheres[b].fine)
            expected[bodies + p] =
                std::min(expected[bodies + p], (world(a, sa) - world(b, sb)).norm() - sa.radius - sb.radius);
      }
      for (int pair = 0; pair < prefilter.pairCount(); ++pair) {
        if (!std::isfinite(expected[pair])) continue;
        const double measured = work.gaps[pair * detail::prefilter::kLanes + lane] + prefilter.margin();
        ASSERT_LE(measured, expected[pair] + tolerance) << "pair " << pair << " batch " << batch;
        if (measured < work.enough[pair] - tolerance) {
          ASSERT_NEAR(measured, expected[pair], tolerance) << "pair " << pair << " batch " << batch;
          ++below;
        } else {
          ++above;
        }
      }
    }
  }
  EXPECT_GT(below, 1000);  // both sides of the thresholds were met
  EXPECT_GT(above, 1000);
}

// A batch loaded at once (both loaders, through SpherePrefilter::loadLanes and directly) holds the very
// floats of its states loaded one by one: full and partial batches, states further apart than their
// joints, angles beyond 2 pi (which loadLane reduces) in some batches.
TEST(SpherePrefilter, LoadingABatchEqualsLoadingItsStatesOneByOne) {
  const auto model = modelOf(sceneFile("thesis_obstacle.yaml"), true);
  const auto& prefilter = prefilterOf(*model);
  const int dof = prefilter.dof(), kLanes = detail::prefilter::kLanes;
  detail::SphereWorkspace batch, single;
  prefilter.prepare(batch);
  prefilter.prepare(single);
  std::mt19937_64 random(43);
  std::uniform_real_distribution<double> angle(-6.0, 6.0), wide(-20.0, 20.0);
  int reduced = 0;
  for (int round = 0; round < 400; ++round) {
    const int lanes = 1 + round % kLanes, stride = dof + round % 3;
    const bool beyond = round % 5 == 0;
    std::vector<double> states(static_cast<std::size_t>(kLanes * stride), NAN);  // the gaps between states: NaN
    for (int lane = 0; lane < lanes; ++lane)
      for (int j = 0; j < dof; ++j)
        states[lane * stride + j] = beyond && j == lane % dof ? wide(random) : angle(random);
    for (int lane = 0; lane < kLanes; ++lane)
      prefilter.loadLane(single, lane, &states[(lane < lanes ? lane : 0) * stride]);
    prefilter.loadLanes(batch, states.data(), stride, lanes);
    ASSERT_EQ(batch.q, single.q) << "round " << round;
    std::vector<float> portable(batch.q.size()), avx2(batch.q.size());
    const bool inRange = detail::prefilter::loadLanesPortable(states.data(), stride, dof, lanes, portable.data());
    bool outside = false;
    for (int lane = 0; lane < lanes; ++lane)
      for (int j = 0; j < dof; ++j) outside = outside || std::abs(states[lane * stride + j]) > 2.0 * M_PI;
    ASSERT_EQ(inRange, !outside) << "round " << round;
    reduced += outside;
    if (inRange) {
      ASSERT_EQ(portable, single.q) << "round " << round;
    }
#if defined(__x86_64__)
    if (prefilter.usesAvx2()) {
      ASSERT_EQ(detail::prefilter::loadLanesAvx2(states.data(), stride, dof, lanes, avx2.data()), inRange);
      if (inRange) {
        ASSERT_EQ(avx2, single.q) << "round " << round;
      }
    }
#endif
  }
  EXPECT_GT(reduced, 40);  // the reducing path was taken too
}

TEST(SpherePrefilter, KernelsAndBatchesTakeTheSameDecisions) {
  const auto model = modelOf(randomScene(3, 12), true);
  const auto& prefilter = prefilterOf(*model);
  const auto& tables = prefilter.tables();
  detail::SphereWorkspace work, single;
  prefilter.prepare(work);
  prefilter.prepare(single);
  std::mt19937_64 random(17);
  std::vector<float> portableGaps(work.gaps.size()), avx2Gaps(work.gaps.size());
  int freeCount = 0;
  for (int batch = 0; batch < 300; ++batch) {
    const std::vector<VectorXd> qs = loadRandomBatch(prefilter, work, model->robot(), random);
    const std::uint32_t portable = detail::prefilter::freeLanesPortable(tables, work.q.data(), 8);
    for (int lane = 0; lane < detail::prefilter::kLanes; ++lane) {
      prefilter.loadLane(single, 0, qs[lane].data());
      const bool alone = detail::prefilter::freeLanesPortable(tables, single.q.data(), 1) != 0;
      ASSERT_EQ(alone, ((portable >> lane) & 1u) != 0) << "batch " << batch << " lane " << lane;
      freeCount += alone;
    }
    std::fill(work.enough.begin(), work.enough.end(), static_cast<float>(batch % 5) * 0.05f);
    detail::prefilter::gapsPortable(tables, work.q.data(), work.enough.data(), portableGaps.data());
#if defined(__x86_64__)
    ASSERT_EQ(prefilter.usesAvx2(), __builtin_cpu_supports("avx2") != 0);
    if (prefilter.usesAvx2()) {
      ASSERT_EQ(detail::prefilter::freeLanesAvx2(tables, work.q.data(), 8), portable) << "batch " << batch;
      detail::prefilter::gapsAvx2(tables, work.q.data(), work.enough.data(), avx2Gaps.data());
      ASSERT_EQ(portableGaps, avx2Gaps) << "batch " << batch;  // the very same bits
    }
#endif
  }
  EXPECT_GT(freeCount, 300);  // the prefilter cleared states, so the comparison compared decisions
}

// The chain's two rotation paths (sphere_kernel_chain.h): the UR10e's rows all take the permuted
// one; the same tables with every row forced onto the general 3×3 path must give gaps within half
// the margin of them (both are bounded by it; measured: the same bits, as the general path's skipped
// terms are exact zeros and its factors ±1), and AVX2 and portable the same bits on the general path.
TEST(SpherePrefilter, PermutedAndGeneralChainPathsAgree) {
  const auto model = modelOf(randomScene(4, 8), true);
  const auto& prefilter = prefilterOf(*model);
  const auto& tables = prefilter.tables();
  std::vector<detail::prefilter::LinkRow> general(tables.links, tables.links + tables.linkCount);
  int permuted = 0;
  for (auto& row : general) {
    permuted += row.permuted;
    row.permuted = 0;
  }
  ASSERT_EQ(permuted, tables.linkCount);  // every UR10e row is a signed permutation about a coordinate axis
  detail::prefilter::Tables generalTables = tables;
  generalTables.links = general.data();
  detail::SphereWorkspace work;
  prefilter.prepare(work);
  std::fill(work.enough.begin(), work.enough.end(), 1e30f);  // fine spheres for every pair
  std::vector<float> fast(work.gaps.size()), slow(work.gaps.size()), other(work.gaps.size());
  std::mt19937_64 random(29);
  double largest = 0.0;
  for (int batch = 0; batch < 300; ++batch) {
    for (int lane = 0; lane < detail::prefilter::kLanes; ++lane) {
      const VectorXd q = arcplan::testing::randomJointState(model->robot(), random);
      prefilter.loadLane(work, lane, q.data());
    }
    detail::prefilter::gapsPortable(tables, work.q.data(), work.enough.data(), fast.data());
    detail::prefilter::gapsPortable(generalTables, work.q.data(), work.enough.data(), slow.data());
    for (std::size_t k = 0; k < fast.size(); ++k)
      largest = std::max(largest, std::abs(static_cast<double>(fast[k]) - slow[k]));
#if defined(__x86_64__)
    if (prefilter.usesAvx2()) {
      detail::prefilter::gapsAvx2(generalTables, work.q.data(), work.enough.data(), other.data());
      ASSERT_EQ(other, slow) << "batch " << batch;
      ASSERT_EQ(detail::prefilter::freeLanesAvx2(generalTables, work.q.data(), 8),
                detail::prefilter::freeLanesPortable(generalTables, work.q.data(), 8))
          << "batch " << batch;
    }
#endif
  }
  EXPECT_LT(largest, prefilter.margin() / 2.0);
}

// Every answer of the prefiltered model is the exact model's, for random states (one by one and in
// batches) and certified motions; the prefilter must also have answered a good share itself.
void expectSameAnswers(const Scene& scene, unsigned seed, int states, int motions) {
  const auto fast = modelOf(scene, true), exact = modelOf(scene, false);
  CollisionData fastData(*fast), exactData(*exact);
  auto& work = *detail::workspaceOf(fastData).spheres;
  std::mt19937_64 random(seed);
  Eigen::MatrixXd batch(fast->robot().dof(), states);
  int cleared = 0, valid = 0;
  for (int k = 0; k < states; ++k) {
    batch.col(k) = arcplan::testing::randomJointState(fast->robot(), random);
    const bool expected = isCollisionFree(*exact, exactData, batch.col(k));
    ASSERT_EQ(isCollisionFree(*fast, fastData, batch.col(k)), expected) << scene.name << " state " << k;
    ASSERT_EQ(collide(*fast, fastData, batch.col(k)).valid, expected);
    cleared += detail::sphereFree(prefilterOf(*fast), work, batch.col(k));
    valid += expected;
  }
  std::vector<bool> free;
  areCollisionFree(*fast, fastData, batch, free);
  for (int k = 0; k < states; ++k) ASSERT_EQ(free[k], isCollisionFree(*exact, exactData, batch.col(k))) << k;
  EXPECT_GT(cleared, valid / 4) << scene.name << ": the prefilter cleared " << cleared << " of " << valid;

  int freeMotions = 0, certified = 0;
  for (int k = 0; k < motions; ++k) {
    VectorXd qa = arcplan::testing::randomJointState(fast->robot(), random);
    if (!isCollisionFree(*exact, exactData, qa)) continue;
    const VectorXd qb = qa + 0.1 * (arcplan::testing::randomJointState(fast->robot(), random) - qa) * (1 + k % 4);
    const bool expected = isMotionCollisionFree(*exact, exactData, qa, qb);
    ASSERT_EQ(isMotionCollisionFree(*fast, fastData, qa, qb), expected) << scene.name << " motion " << k;
    double fastLast = -1.0, exactLast = -1.0;
    ASSERT_EQ(isMotionCollisionFree(*fast, fastData, qa, qb, &fastLast),
              isMotionCollisionFree(*exact, exactData, qa, qb, &exactLast));
    EXPECT_EQ(fastLast, exactLast);
    freeMotions += expected;
    certified +=
        detail::sphereMotion(*fast, detail::workspaceOf(fastData), qa, qb, 0.001, false) == detail::SphereMotion::Free;
  }
  // Motions were free, and the spheres certified some themselves (the batched check was exercised).
  EXPECT_GE(freeMotions, 5) << scene.name;
  EXPECT_GT(certified, freeMotions / 4) << scene.name << ": " << certified << " of " << freeMotions;
}

TEST(SpherePrefilter, SameAnswersAsFclOnTheThesisScenes) {
  expectSameAnswers(sceneFile("thesis_obstacle.yaml"), 1, 3000, 150);
  expectSameAnswers(sceneFile("thesis_free.yaml"), 2, 3000, 150);
}

TEST(SpherePrefilter, SameAnswersAsFclWithBoxesCylindersSpheresAndMeshes) {
  for (unsigned seed = 10; seed < 13; ++seed) expectSameAnswers(randomScene(seed, 5), seed, 2000, 100);
}

TEST(SpherePrefilter, ExactOnlyModelHasNoPrefilterAndABatchNeedsTheRightRowCount) {
  const auto exact = modelOf(sceneFile("thesis_obstacle.yaml"), false);
  EXPECT_EQ(detail::implementationOf(*exact).prefilter, nullptr);
  CollisionData data(*exact);
  std::vector<bool> free;
  EXPECT_THROW(areCollisionFree(*exact, data, Eigen::MatrixXd::Zero(5, 3), free), arcplan::Error);
}

}  // namespace
