// detail::linkVelocity and detail::planeReach (collision/src/motion_bounds.h): how fast a link's points move at one
// state of a straight joint motion, and how far along the motion a robot part stays clear of an obstacle, or of a link
// nearer the base, by the plane between them. The velocity is compared with central differences of forward
// kinematics; the reach with FCL's exact distances at states spread over it: beside MotionBenchMaker's shelf boards,
// where the gripper slides along a board (reads ARCPLAN_SHARED_DATA's mbm_ur5, as the other board tests do), and
// between the thesis UR10e's own links.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>

#include <gtest/gtest.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/kinematics.h"
#include "model_implementation.h"  // collision/src
#include "motion_bounds.h"         // collision/src
#include "parts.h"                 // collision/src
#include "support/command.h"
#include "support/random_joint_state.h"

namespace {

using namespace arcplan::collision;
using Eigen::VectorXd;
namespace fs = std::filesystem;

struct Shelf {
  std::shared_ptr<const CollisionModel> model;
  VectorXd goal;  // a grasp between two boards
};

// bookshelf_thin 0004: its goal reaches between boards 4 cm apart.
Shelf thinShelf() {
  const fs::path mbm = arcplan::testing::sharedDataDirectory() / "mbm_ur5";
  const fs::path folder = mbm / "problems" / "bookshelf_thin_ur5";
  const MoveItRobot robot{mbm / "ur5.urdf", mbm / "ur5.srdf"};
  MoveItProblem problem = loadMoveItProblem(folder / "scene0004.yaml", folder / "request0004.yaml", robot);
  const VectorXd goal = *problem.scene.queries.front().goal.joints;
  return {makeCollisionModel(std::move(problem.scene)), goal};
}

std::shared_ptr<const CollisionModel> thesisFree() {
  return makeCollisionModel(loadScene(arcplan::dataDirectory() / "scenes" / "thesis_free.yaml"));
}

Eigen::Isometry3d partPose(const detail::Implementation& impl, const arcplan::robot::KinematicsData& kinematics,
                           int part) {
  return kinematics.linkPoses[impl.robotPartLink[part]] * impl.robotParts[part].offset;
}

TEST(PlaneReach, LinkVelocityIsTheDerivativeOfForwardKinematics) {
  const Shelf shelf = thinShelf();
  const CollisionModel& model = *shelf.model;
  const auto& impl = detail::implementationOf(model);
  const auto& robot = model.robot();
  arcplan::robot::KinematicsData at(robot), ahead(robot), behind(robot);
  std::mt19937_64 random(61);
  constexpr double h = 1e-6;
  int compared = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const VectorXd q = arcplan::testing::randomJointState(robot, random);
    VectorXd delta(robot.dof());
    for (int j = 0; j < robot.dof(); ++j) delta[j] = std::uniform_real_distribution<double>(-1.0, 1.0)(random);
    arcplan::robot::forwardKinematics(robot, q, at);
    arcplan::robot::forwardKinematics(robot, q + h * delta, ahead);
    arcplan::robot::forwardKinematics(robot, q - h * delta, behind);
    for (std::size_t i = 0; i < impl.robotParts.size(); ++i) {
      const detail::Part& part = impl.robotParts[i];
      const int body = part.body;
      const int link = impl.robotPartLink[i];
      const detail::LinkVelocity velocity = detail::linkVelocity(robot, impl, body, at.linkPoses, delta);
      for (const Eigen::Vector3d& vertex : part.hullPoints) {
        const Eigen::Vector3d local = part.offset * vertex;
        const Eigen::Vector3d differenced =
            (ahead.linkPoses[link] * local - behind.linkPoses[link] * local) / (2.0 * h);
        const Eigen::Vector3d p = at.linkPoses[link] * local;
        const Eigen::Vector3d predicted = velocity.angular.cross(p) + velocity.linear;
        ASSERT_LT((predicted - differenced).norm(), 1e-6 * (1.0 + differenced.norm()))
            << model.linkNames()[body] << " trial " << trial;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 1000);
}

TEST(PlaneReach, NoPartComesCloserThanTheClearanceWithinItsReach) {
  const Shelf shelf = thinShelf();
  const CollisionModel& model = *shelf.model;
  const auto& impl = detail::implementationOf(model);
  const auto& robot = model.robot();
  const auto& options = model.options();
  constexpr double m = 0.002;  // the clearance asked for
  constexpr double kGjkError = 1e-6;
  constexpr int kSamples = 40;
  arcplan::robot::KinematicsData at(robot), along(robot);
  std::mt19937_64 random(67);
  std::normal_distribution<double> gaussian;
  int measured = 0, longer = 0;
  for (int trial = 0; trial < 400 && measured < 150; ++trial) {
    // States about the grasp between the boards, on RRTConnect-sized motions (0.35 rad) through them.
    VectorXd q = shelf.goal, direction(robot.dof());
    for (int j = 0; j < robot.dof(); ++j) {
      q[j] += std::uniform_real_distribution<double>(-0.15, 0.15)(random);
      direction[j] = gaussian(random);
    }
    const VectorXd delta = 0.35 * direction.normalized();
    const double s = std::uniform_real_distribution<double>(0.0, 1.0)(random);
    const VectorXd qa = q - s * delta;
    arcplan::robot::forwardKinematics(robot, q, at);
    const VectorXd step = delta.cwiseAbs();
    for (std::size_t k = 0; k < impl.obstacleGroups.size(); ++k) {
      const auto& group = impl.obstacleGroups[k];
      const detail::LinkVelocity velocity = detail::linkVelocity(robot, impl, group.firstBody, at.linkPoses, delta);
      const double curvature = detail::linkCurvature(impl, group.firstBody, step);
      for (std::size_t p = 0; p < group.parts.size(); ++p) {
        const auto [i, j] = group.parts[p];
        const detail::Part &part = impl.robotParts[i], &obstacle = impl.obstacleParts[j];
        const Eigen::Isometry3d pose = partPose(impl, at, i), &obstaclePose = obstacle.offset;
        // The direction as the certified check finds it: the hulls' GJK, or the convex parts' own.
        Eigen::Vector3d axis = Eigen::Vector3d::Zero();
        double d = detail::hullGap(part, pose, obstacle, obstaclePose, options, 1.0, axis);
        if (axis.isZero()) d = detail::partsDistance(part, pose, obstacle, obstaclePose, false, options, &axis);
        if (!(d > m && d < 0.05) || axis.isZero()) continue;
        const double reach = detail::planeReach(part, pose, obstacle, obstaclePose, axis, velocity, curvature, m);
        ++measured;
        // The distance over the part pair's rate (every joint's full reach), which the certified check takes without
        // it.
        const double rate = impl.partPairReach.row(impl.firstPartPair[k] + static_cast<Eigen::Index>(p)).dot(step);
        if (reach > (d - m) / rate) ++longer;
        const double from = std::max(0.0, s - reach), to = std::min(1.0, s + reach);
        for (int n = 0; n <= kSamples; ++n) {
          const double t = from + (to - from) * n / kSamples;
          arcplan::robot::forwardKinematics(robot, qa + t * delta, along);
          const double distance =
              detail::partsDistance(part, partPose(impl, along, i), obstacle, obstaclePose, true, options);
          ASSERT_GE(distance, m - kGjkError) << model.linkNames()[group.firstBody] << " trial " << trial << " at " << t
                                             << " of the reach " << reach << " about " << s;
        }
      }
    }
  }
  // Not vacuous: hundreds of part pairs within 5 cm of a board or the shelf, and on many the plane lets the certificate
  // run farther than the distance over the rate does.
  std::cout << "plane reach: " << measured << " part pairs, longer on " << longer << "\n";
  EXPECT_GE(measured, 100);
  EXPECT_GE(longer, measured / 4) << longer << " of " << measured;
}

TEST(PlaneReach, ALinkKeepsItsClearanceFromANearerLinkWithinItsReach) {
  const auto model = thesisFree();
  const auto& impl = detail::implementationOf(*model);
  const auto& robot = model->robot();
  const auto& options = model->options();
  constexpr double m = 0.001;  // a self pair's clearance at most (kSelfClearance)
  constexpr double kGjkError = 1e-6;
  constexpr int kSamples = 40;
  arcplan::robot::KinematicsData at(robot), along(robot);
  std::mt19937_64 random(71);
  std::normal_distribution<double> gaussian;
  int measured = 0, longer = 0;
  for (int trial = 0; trial < 3000 && measured < 150; ++trial) {
    const VectorXd q = arcplan::testing::randomJointState(robot, random);
    VectorXd direction(robot.dof());
    for (int j = 0; j < robot.dof(); ++j) direction[j] = gaussian(random);
    // A planner's edges (0.35 rad) and the long motions of the benchmarks (1.5 rad).
    const VectorXd delta = (trial % 2 == 0 ? 0.35 : 1.5) * direction.normalized();
    const double s = std::uniform_real_distribution<double>(0.0, 1.0)(random);
    const VectorXd qa = q - s * delta, step = delta.cwiseAbs();
    arcplan::robot::forwardKinematics(robot, q, at);
    for (std::size_t g = 0; g < impl.selfGroups.size(); ++g) {
      const auto& group = impl.selfGroups[g];
      if (group.rigid) continue;
      const bool firstMoves = detail::movesWith(impl, group.firstBody, group.secondBody);
      if (!firstMoves && !detail::movesWith(impl, group.secondBody, group.firstBody)) continue;
      const int mover = firstMoves ? group.firstBody : group.secondBody;
      const int still = firstMoves ? group.secondBody : group.firstBody;
      const detail::LinkVelocity velocity = detail::linkVelocity(robot, impl, mover, at.linkPoses, delta, still);
      const double curvature = detail::linkCurvature(impl, mover, step, still);
      for (std::size_t p = 0; p < group.parts.size(); ++p) {
        const int i = firstMoves ? group.parts[p].first : group.parts[p].second;
        const int j = firstMoves ? group.parts[p].second : group.parts[p].first;
        const detail::Part &moving = impl.robotParts[i], &standing = impl.robotParts[j];
        const Eigen::Isometry3d pose = partPose(impl, at, i), standingPose = partPose(impl, at, j);
        Eigen::Vector3d axis = Eigen::Vector3d::Zero();
        double d = detail::hullGap(moving, pose, standing, standingPose, options, 1.0, axis);
        if (axis.isZero()) d = detail::partsDistance(moving, pose, standing, standingPose, false, options, &axis);
        if (!(d > m && d < 0.05) || axis.isZero()) continue;
        const double reach = detail::planeReach(moving, pose, standing, standingPose, axis, velocity, curvature, m);
        ++measured;
        const auto pair = static_cast<Eigen::Index>(impl.firstPartPair[impl.obstacleGroups.size() + g] + p);
        if (reach > (d - m) / impl.partPairReach.row(pair).dot(step)) ++longer;
        const double from = std::max(0.0, s - reach), to = std::min(1.0, s + reach);
        for (int n = 0; n <= kSamples; ++n) {
          const double t = from + (to - from) * n / kSamples;
          arcplan::robot::forwardKinematics(robot, qa + t * delta, along);
          const double distance = detail::partsDistance(moving, partPose(impl, along, i), standing,
                                                        partPose(impl, along, j), true, options);
          ASSERT_GE(distance, m - kGjkError)
              << model->linkNames()[mover] << " from " << model->linkNames()[still] << " trial " << trial << " at " << t
              << " of the reach " << reach << " about " << s;
        }
      }
    }
  }
  std::cout << "plane reach, self pairs: " << measured << " part pairs, longer on " << longer << "\n";
  EXPECT_GE(measured, 100);
  EXPECT_GE(longer, measured / 4) << longer << " of " << measured;
}

}  // namespace
