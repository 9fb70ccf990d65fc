// Queries beside MotionBenchMaker's shelf boards and cans, where RRTConnect's 1 cm checks spend their time: the
// witness points that refuse a gripper part inside the clearance without an exact distance (witnessCloser), the sphere
// rake's exact check of the pairs its spheres leave open, and the self pairs it leaves to the exact check. Each is
// compared with FCL: witness distances with FCL's sphere–box, sphere–cylinder and sphere–sphere distances (through
// partsDistance) and its mesh–primitive distances, state answers with a model that has every layer off, motion
// answers with the same model without the spheres. Reads ARCPLAN_SHARED_DATA's mbm_ur5, as the containing-mesh
// layer's tests do.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>

#include <fcl/fcl.h>
#include <gtest/gtest.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/collision/moveit_scene.h"
#include "model_implementation.h"  // collision/src
#include "sphere_prefilter.h"      // collision/src
#include "support/collision_options.h"
#include "support/command.h"
#include "support/random_joint_state.h"
#include "support/separating_direction.h"

namespace {

using namespace arcplan::collision;
namespace fs = std::filesystem;

struct ShelfProblem {
  Scene scene;
  Eigen::VectorXd goal;  // a grasp between two boards
};

// bookshelf_thin 0004: its goal reaches between boards 4 cm apart (RRTConnect's slowest thin problem at 1 cm).
ShelfProblem thinShelf() {
  const fs::path mbm = arcplan::testing::sharedDataDirectory() / "mbm_ur5";
  const fs::path folder = mbm / "problems" / "bookshelf_thin_ur5";
  const MoveItRobot robot{mbm / "ur5.urdf", mbm / "ur5.srdf"};
  MoveItProblem problem = loadMoveItProblem(folder / "scene0004.yaml", folder / "request0004.yaml", robot);
  const Eigen::VectorXd goal = *problem.scene.queries.front().goal.joints;
  return {std::move(problem.scene), goal};
}

// The distance of a point from an obstacle part, by FCL (a sphere of radius r about the point, r added back).
double pointDistance(const Eigen::Vector3d& point, const detail::Part& obstacle, const Eigen::Isometry3d& obstaclePose,
                     const CollisionModelOptions& options) {
  constexpr double r = 1e-6;
  static const detail::Part ball = detail::spherePart(r, options.distanceBoundingVolume);
  Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
  at.translation() = point;
  return detail::partsDistance(ball, at, obstacle, obstaclePose, true, options) + r;
}

// The distance of the nearest of `points` (of `part`, placed at `pose`) from `obstacle` (at the origin), by FCL: never
// below the part's own (FCL's exact distance), and witnessCloser answers by it.
double nearestWitness(const detail::Part& part, const Eigen::Isometry3d& pose,
                      const std::vector<Eigen::Vector3d>& points, const detail::Part& obstacle,
                      const CollisionModelOptions& options) {
  const Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  double nearest = INFINITY;
  for (const auto& point : points) nearest = std::min(nearest, pointDistance(pose * point, obstacle, origin, options));
  EXPECT_GE(nearest, detail::partsDistance(part, pose, obstacle, origin, true, options) - 1e-6);
  EXPECT_TRUE(detail::witnessCloser(part, pose, obstacle, origin, nearest + 1e-6));
  if (nearest > 1e-6) {
    EXPECT_FALSE(detail::witnessCloser(part, pose, obstacle, origin, nearest - 1e-6));
  }
  return nearest;
}

// Every witness point is a vertex of its part, so its distance from a board bounds the part's from above (checked
// against FCL's mesh–box distance), and witnessCloser answers by the nearest witness, measured by FCL.
TEST(NearBoards, WitnessPointsAreVerticesWhoseDistanceBoundsThePartsFromAbove) {
  const auto model = makeCollisionModel(thinShelf().scene);
  const auto& impl = detail::implementationOf(*model);
  const Eigen::Vector3d size(0.8, 0.02, 0.4);  // a board of MBM's shelves
  detail::Part board = detail::boxPart(size);
  board.boxBound = true;
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int parts = 0, closer = 0, poses = 0;
  for (const auto& part : impl.robotParts) {
    if (part.witnessPoints.empty()) continue;
    ++parts;
    for (const auto& witness : part.witnessPoints)
      ASSERT_NE(std::find(part.hullPoints.begin(), part.hullPoints.end(), witness), part.hullPoints.end());
    const double reach = (part.capsule.end - part.capsule.start).norm() / 2.0 + part.capsule.radius;
    for (int k = 0; k < 20; ++k) {
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random)).normalized().matrix();
      // The part's centre within its reach + 3 cm of the board's face, anywhere along the board.
      const Eigen::Vector3d centre = pose * ((part.capsule.start + part.capsule.end) / 2.0);
      pose.translation() +=
          Eigen::Vector3d(0.3 * unit(random),
                          size.y() / 2 + reach * (0.5 + 0.5 * unit(random)) + 0.03 * (1.0 + unit(random)) / 2.0,
                          0.15 * unit(random)) -
          centre;
      SCOPED_TRACE("part " + std::to_string(parts) + " pose " + std::to_string(k));
      closer += nearestWitness(part, pose, part.witnessPoints, board, model->options()) < 0.0105;
      ++poses;
    }
  }
  EXPECT_GT(parts, 10);
  EXPECT_GT(closer, poses / 10);  // poses inside a 1 cm clearance (plus margin) were tried
}

// Against a can (MBM's 3 cm cylinders) or a ball every vertex of a part is a witness: the nearest one's distance (by
// FCL) is never below the part's (FCL's mesh–cylinder / mesh–sphere distance), and witnessCloser answers by it.
TEST(NearBoards, AnyVertexNearACanOrABallBoundsThePartsDistanceFromAbove) {
  const auto model = makeCollisionModel(thinShelf().scene);
  const auto& impl = detail::implementationOf(*model);
  const CollisionModelOptions& options = model->options();
  const detail::Part can = detail::cylinderPart(0.03, 0.14, options.distanceBoundingVolume),
                     ball = detail::spherePart(0.04, options.distanceBoundingVolume);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int parts = 0, closer = 0, poses = 0;
  for (const auto& part : impl.robotParts) {
    if (part.hullPoints.empty()) continue;
    ++parts;
    const double reach = (part.capsule.end - part.capsule.start).norm() / 2.0 + part.capsule.radius;
    for (int k = 0; k < 6; ++k) {
      const detail::Part& obstacle = k % 2 == 0 ? can : ball;
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random)).normalized().matrix();
      // The part's centre between 3 cm inside and its reach + 3 cm outside the obstacle's side, at any height.
      const Eigen::Vector3d centre = pose * ((part.capsule.start + part.capsule.end) / 2.0);
      const double radial = 0.03 + (reach + 0.03) * (1.0 + unit(random)) / 2.0 - 0.03 * (1.0 + unit(random)) / 2.0;
      const double angle = M_PI * unit(random);
      pose.translation() +=
          Eigen::Vector3d(radial * std::cos(angle), radial * std::sin(angle), 0.06 * unit(random)) - centre;
      SCOPED_TRACE("part " + std::to_string(parts) + " pose " + std::to_string(k));
      closer += nearestWitness(part, pose, part.hullPoints, obstacle, options) < 0.0105;
      ++poses;
    }
  }
  EXPECT_GT(parts, 10);
  EXPECT_GT(closer, poses / 10);  // poses inside a 1 cm clearance (plus margin) were tried
}

// hasClearance at 1 cm on states around the grasp (witnesses refuse the ones whose gripper reaches within the
// clearance of a board) answers by the clearance rule on FCL's distances on the meshes.
TEST(NearBoards, HasClearanceBesideTheBoardsIsThatOfFcl) {
  const ShelfProblem problem = thinShelf();
  const auto layered = makeCollisionModel(problem.scene),
             exact = makeCollisionModel(problem.scene, arcplan::testing::exactOnly());
  CollisionData layeredData(*layered), exactData(*exact);
  std::mt19937_64 random(11);
  std::normal_distribution<double> gaussian(0.0, 0.04);
  int within = 0, clear = 0;
  for (int k = 0; k < 120; ++k) {
    Eigen::VectorXd q = problem.goal;
    for (int j = 0; j < q.size(); ++j) q[j] += gaussian(random);
    const DistanceReport report = distance(*exact, exactData, q);
    const bool rule = report.obstacleDistance >= 0.01 && report.selfDistance >= 0.001;
    ASSERT_EQ(hasClearance(*layered, layeredData, q, 0.01), rule) << "state " << k << " " << report.obstacleDistance;
    within += report.obstacleDistance > 0.0 && report.obstacleDistance < 0.01;
    clear += rule;
  }
  EXPECT_GT(within, 10);  // the band the witnesses decide in
  EXPECT_GT(clear, 10);
}

// thin 0004's shelf as the default model and without the sphere prefilter (the reference of the motion answers), and
// certified motions at 1 cm.
struct ShelfWithAndWithoutSpheres {
  static CollisionModelOptions withoutSpheres() {
    CollisionModelOptions options;
    options.spherePrefilter = false;
    return options;
  }
  ShelfProblem problem = thinShelf();
  std::shared_ptr<const CollisionModel> layered = makeCollisionModel(problem.scene),
                                        plain = makeCollisionModel(problem.scene, withoutSpheres());
  CollisionData layeredData{*layered}, plainData{*plain};
  MotionCheckOptions options = [] {
    MotionCheckOptions atOneCentimetre;
    atOneCentimetre.minimumClearance = 0.01;
    return atOneCentimetre;
  }();
};

// Certified 0.35 rad motions around the grasp (RRTConnect's range in the mbm-ur5 suite) at 1 cm: the sphere rake in
// front of the exact check (its collision search checks only the pairs its spheres leave open) takes the answers
// the exact check takes without it.
TEST(NearBoards, CertifiedMotionsAnswerAsWithoutTheSpheres) {
  ShelfWithAndWithoutSpheres shelf;
  std::mt19937_64 random(13);
  std::normal_distribution<double> gaussian;
  int accepted = 0, motions = 0;
  while (motions < 150) {
    Eigen::VectorXd start = shelf.problem.goal, direction(shelf.problem.goal.size());
    for (int j = 0; j < start.size(); ++j) start[j] += 0.15 * gaussian(random);
    if (!hasClearance(*shelf.plain, shelf.plainData, start, 0.01)) continue;
    for (int j = 0; j < direction.size(); ++j) direction[j] = gaussian(random);
    const Eigen::VectorXd end = start + 0.35 * direction.normalized();
    const bool expected = isMotionCollisionFree(*shelf.plain, shelf.plainData, start, end, nullptr, shelf.options);
    ASSERT_EQ(isMotionCollisionFree(*shelf.layered, shelf.layeredData, start, end, nullptr, shelf.options), expected)
        << motions;
    accepted += expected;
    ++motions;
  }
  EXPECT_GT(accepted, 10);  // both answers occur
  EXPECT_LT(accepted, motions - 10);
}

// The hull distance's bound along a direction (separatingGap): below FCL's GJK distance of the two hulls for any
// direction, within a few micrometres of it along the direction GJK found (hullGap keeps it per part pair), and
// still below it after the arm moved on — on the self part pairs of random MBM states.
TEST(NearBoards, ADirectionBoundsTheHullsDistanceFromBelow) {
  const auto model = makeCollisionModel(thinShelf().scene);
  const auto& impl = detail::implementationOf(*model);
  CollisionData workspace(*model);
  auto& data = detail::workspaceOf(workspace);
  static const fcl::DistanceRequestd request(false, false, 0.0, 0.0, 1e-9);
  const auto hullDistance = [&](const detail::Part& a, const Eigen::Isometry3d& poseA, const detail::Part& b,
                                const Eigen::Isometry3d& poseB) {
    fcl::DistanceResultd result;  // FCL answers -1 for hulls that intersect
    return std::max(fcl::distance(a.hullGeometry.get(), poseA, b.hullGeometry.get(), poseB, request, result), 0.0);
  };
  std::mt19937_64 random(23);
  std::normal_distribution<double> gaussian;
  int measured = 0, tight = 0;
  for (int k = 0; k < 40; ++k) {
    const Eigen::VectorXd q = arcplan::testing::randomJointState(model->robot(), random);
    Eigen::VectorXd moved = q;
    for (int j = 0; j < moved.size(); ++j) moved[j] += 0.02 * gaussian(random);
    for (std::size_t pair = 0; pair < impl.partPairs.size(); ++pair) {
      const auto& partPair = impl.partPairs[pair];
      if (!partPair.group->self) continue;
      const detail::Part &a = impl.robotParts[partPair.first], &b = impl.robotParts[partPair.second];
      if (detail::separatingGap(a, Eigen::Isometry3d::Identity(), b, Eigen::Isometry3d::Identity(),
                                Eigen::Vector3d::UnitX()) == -INFINITY ||
          (a.convexGeometry && b.convexGeometry))
        continue;  // not two fcl::Convex hulls, or convex parts (measured exactly, without hull bounds)
      detail::updateRobot(*model, data, q);
      detail::boundGap(impl, data, partPair.first, partPair.second, true);  // places both parts
      const Eigen::Isometry3d poseA = data.partPoses[partPair.first], poseB = data.partPoses[partPair.second];
      const double exact = hullDistance(a, poseA, b, poseB);
      if (!(exact > 1e-4)) continue;
      Eigen::Vector3d axis = Eigen::Vector3d::Zero();
      detail::hullGap(a, poseA, b, poseB, model->options(), INFINITY, axis);  // GJK on the hulls: keeps the direction
      const Eigen::Vector3d any = Eigen::Vector3d(gaussian(random), gaussian(random), gaussian(random)).normalized();
      tight += arcplan::testing::separatingDirectionHolds(a, poseA, b, poseB, axis, any, exact);
      ++measured;
      detail::updateRobot(*model, data, moved);
      detail::boundGap(impl, data, partPair.first, partPair.second, true);
      const Eigen::Isometry3d &movedA = data.partPoses[partPair.first], &movedB = data.partPoses[partPair.second];
      ASSERT_LE(detail::separatingGap(a, movedA, b, movedB, axis), hullDistance(a, movedA, b, movedB) + 1e-6);
    }
  }
  EXPECT_GT(measured, 200);
  EXPECT_GT(tight, measured * 9 / 10) << tight << " of " << measured;
}

// Certified 0.35 rad motions from random states at 1 cm: base_link – upper_arm_link and forearm_link – wrist_2_link are
// never 1.8 cm apart, so their spheres overlap in every state. Their floor grids separate them where a cell's floor
// keeps the clearance; elsewhere, and for other self pairs too close for their spheres, the rake leaves them to the
// exact check (PairsLeft), which follows them alone. The
// answers stay those taken without spheres — the last valid state too, where the rake defers nothing.
TEST(NearBoards, SelfPairsTheSpheresCannotSeparateAreLeftToFloorsOrTheExactCheck) {
  ShelfWithAndWithoutSpheres shelf;
  std::mt19937_64 random(17);
  std::normal_distribution<double> gaussian;
  int accepted = 0, motions = 0, certified = 0, left = 0;
  while (motions < 200) {
    const Eigen::VectorXd start = arcplan::testing::randomJointState(shelf.layered->robot(), random);
    if (!hasClearance(*shelf.plain, shelf.plainData, start, 0.01)) continue;
    Eigen::VectorXd direction(start.size());
    for (int j = 0; j < direction.size(); ++j) direction[j] = gaussian(random);
    const Eigen::VectorXd end = start + 0.35 * direction.normalized();
    const bool expected = isMotionCollisionFree(*shelf.plain, shelf.plainData, start, end, nullptr, shelf.options);
    ASSERT_EQ(isMotionCollisionFree(*shelf.layered, shelf.layeredData, start, end, nullptr, shelf.options), expected)
        << motions;
    double layeredLast = -1.0, plainLast = -1.0;
    ASSERT_EQ(isMotionCollisionFree(*shelf.layered, shelf.layeredData, start, end, &layeredLast, shelf.options),
              isMotionCollisionFree(*shelf.plain, shelf.plainData, start, end, &plainLast, shelf.options));
    EXPECT_EQ(layeredLast, plainLast) << motions;
    auto& workspace = detail::workspaceOf(shelf.layeredData);
    const detail::SphereMotion spheres = detail::sphereMotion(*shelf.layered, workspace, start, end, 0.01, true);
    certified += expected && spheres == detail::SphereMotion::Free;
    left += expected && spheres == detail::SphereMotion::PairsLeft;
    accepted += expected;
    ++motions;
  }
  EXPECT_GT(accepted, 50);
  std::cerr << accepted << " accepted: " << certified << " certified by spheres and floors, " << left << " left\n";
  EXPECT_GT(certified + left, accepted * 9 / 10) << "the rake settled the obstacles of most accepted motions";
  // (Without the grids none: the two pairs' spheres overlap everywhere. The motions left mostly bring other self pairs
  // close too, pairs three or more joints apart, which have no grid.)
  EXPECT_GT(certified, accepted / 3) << "the floor grids separated the close self pairs on many accepted motions";
}

}  // namespace
