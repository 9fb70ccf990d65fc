// detail::linkVelocity, detail::planeReach and the bounding volumes' planes (collision/src/motion_bounds.h): how fast
// a link's points move at one state of a straight joint motion, and how far along the motion a robot part stays clear
// of an obstacle, or of a link nearer the base, by a plane between them (the hulls' from GJK's direction, or the
// bounding capsules' and boxes'). The velocity is compared with central differences of forward kinematics; the planes
// with points sampled in the volumes and with the bounds the certified check takes; the reaches with FCL's exact
// distances at states spread over them: beside MotionBenchMaker's shelf boards, where the gripper slides along a board
// (reads ARCPLAN_SHARED_DATA's mbm_ur5, as the other board tests do), and between the thesis UR10e's own links.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>
#include <vector>

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

// The distance of two parts and the direction between them as the certified check finds them: the hulls' GJK, or the
// convex parts' own (`axis` zero where neither gives one).
double gapAndDirection(const detail::Part& a, const Eigen::Isometry3d& poseA, const detail::Part& b,
                       const Eigen::Isometry3d& poseB, const CollisionModelOptions& options, Eigen::Vector3d& axis) {
  axis.setZero();
  const double d = detail::hullGap(a, poseA, b, poseB, options, 1.0, axis);
  return axis.isZero() ? detail::partsDistance(a, poseA, b, poseB, false, options, &axis) : d;
}

// Whether FCL's distance between parts i and j (a robot part, and a robot part or, with `obstacle`, an obstacle part)
// stays at least m on the motion qa + t·delta at 41 values of t spread over s ± reach (within [0, 1]).
::testing::AssertionResult apartWithin(const CollisionModel& model, int i, int j, bool obstacle, const VectorXd& qa,
                                       const VectorXd& delta, double s, double reach, double m) {
  constexpr double kGjkError = 1e-6;
  constexpr int kSamples = 40;
  const auto& impl = detail::implementationOf(model);
  arcplan::robot::KinematicsData along(model.robot());
  const double from = std::max(0.0, s - reach), to = std::min(1.0, s + reach);
  for (int n = 0; n <= kSamples; ++n) {
    const double t = from + (to - from) * n / kSamples;
    arcplan::robot::forwardKinematics(model.robot(), qa + t * delta, along);
    const double distance =
        obstacle ? detail::partsDistance(impl.robotParts[i], partPose(impl, along, i), impl.obstacleParts[j],
                                         impl.obstacleParts[j].offset, true, model.options())
                 : detail::partsDistance(impl.robotParts[i], partPose(impl, along, i), impl.robotParts[j],
                                         partPose(impl, along, j), true, model.options());
    if (distance < m - kGjkError) {
      return ::testing::AssertionFailure()
             << "distance " << distance << " at " << t << " of the reach " << reach << " about " << s << " ("
             << model.linkNames()[impl.robotParts[i].body] << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

// Points of a capsule (segment start–end, radius): its ends pushed out along ±direction, and random ones inside.
std::vector<Eigen::Vector3d> capsulePoints(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius,
                                           const Eigen::Vector3d& direction, std::mt19937_64& random) {
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& centre : {start, end}) {
    points.push_back(centre + radius * direction);
    points.push_back(centre - radius * direction);
  }
  std::normal_distribution<double> gaussian;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int n = 0; n < 200; ++n) {
    const Eigen::Vector3d offset(gaussian(random), gaussian(random), gaussian(random));
    points.push_back(start + unit(random) * (end - start) + radius * std::cbrt(unit(random)) * offset.normalized());
  }
  return points;
}

// Whether a bounding volumes' plane with a gap has every point of the other volume at least that gap beyond every
// point of the moving one along its normal, and the gap is `bound` (the check's bound of the two volumes); without a
// gap, whether the bound says the volumes touch.
::testing::AssertionResult separates(const detail::BoundingPlane& plane, double bound,
                                     const std::vector<Eigen::Vector3d>& moving,
                                     const std::vector<Eigen::Vector3d>& other) {
  if (!(plane.gap > 0.0)) {
    if (bound <= 2e-6) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "no plane, bound " << bound;
  }
  if (std::abs(plane.gap - bound) > 2e-6) return ::testing::AssertionFailure() << plane.gap << " vs bound " << bound;
  double highest = -1e9, lowest = 1e9;
  for (const auto& x : moving) highest = std::max(highest, plane.normal.dot(x));
  for (const auto& x : other) lowest = std::min(lowest, plane.normal.dot(x));
  if (lowest - highest < plane.gap - 1e-12) {
    return ::testing::AssertionFailure() << "apart by " << lowest - highest << " along the normal, gap " << plane.gap;
  }
  return ::testing::AssertionSuccess();
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
  arcplan::robot::KinematicsData at(robot);
  std::mt19937_64 random(67);
  std::normal_distribution<double> gaussian;
  int measured = 0, longer = 0, bounded = 0;
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
        Eigen::Vector3d axis;
        const double d = gapAndDirection(part, pose, obstacle, obstaclePose, options, axis);
        if (!(d > m && d < 0.05) || axis.isZero()) continue;
        const double reach = detail::planeReach(part, pose, obstacle, obstaclePose, axis, velocity, curvature, m);
        ++measured;
        // The distance over the part pair's rate (every joint's full reach), which the certified check takes without
        // it.
        const double rate = impl.partPairReach.row(impl.firstPartPair[k] + static_cast<Eigen::Index>(p)).dot(step);
        if (reach > (d - m) / rate) ++longer;
        ASSERT_TRUE(apartWithin(model, i, j, true, qa, delta, s, reach, m)) << "trial " << trial;
        // The plane of the bounding volumes, from the capsule around the part.
        const Eigen::Vector3d start = pose * part.capsule.start, end = pose * part.capsule.end;
        const detail::BoundingPlane plane =
            obstacle.boxBound ? detail::capsuleBoxPlane(start, end, part.capsule.radius, impl.obstacleInversePoses[j],
                                                        obstacle.boxHalfExtents)
                              : detail::capsulesPlane(start, end, part.capsule.radius, impl.obstacleCapsuleStarts[j],
                                                      impl.obstacleCapsuleEnds[j], obstacle.capsule.radius);
        const double bounding =
            detail::capsulePlaneReach(start, end, part.capsule.radius, plane, velocity, curvature, m);
        if (bounding > 0.0) ++bounded;
        ASSERT_TRUE(apartWithin(model, i, j, true, qa, delta, s, bounding, m)) << "bounding, trial " << trial;
      }
    }
  }
  // Not vacuous: hundreds of part pairs within 5 cm of a board or the shelf, and on many the plane lets the certificate
  // run farther than the distance over the rate does; the bounding volumes leave a plane on some.
  std::cout << "plane reach: " << measured << " part pairs, longer on " << longer << ", bounding planes " << bounded
            << "\n";
  EXPECT_GE(measured, 100);
  EXPECT_GE(bounded, 10);
  EXPECT_GE(longer, measured / 4) << longer << " of " << measured;
}

TEST(PlaneReach, ALinkKeepsItsClearanceFromANearerLinkWithinItsReach) {
  const auto model = thesisFree();
  const auto& impl = detail::implementationOf(*model);
  const auto& robot = model->robot();
  const auto& options = model->options();
  constexpr double m = 0.001;  // a self pair's clearance at most (kSelfClearance)
  arcplan::robot::KinematicsData at(robot);
  std::mt19937_64 random(71);
  std::normal_distribution<double> gaussian;
  int measured = 0, longer = 0, bounded = 0;
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
        Eigen::Vector3d axis;
        const double d = gapAndDirection(moving, pose, standing, standingPose, options, axis);
        if (!(d > m && d < 0.05) || axis.isZero()) continue;
        const double reach = detail::planeReach(moving, pose, standing, standingPose, axis, velocity, curvature, m);
        ++measured;
        const auto pair = static_cast<Eigen::Index>(impl.firstPartPair[impl.obstacleGroups.size() + g] + p);
        if (reach > (d - m) / impl.partPairReach.row(pair).dot(step)) ++longer;
        ASSERT_TRUE(apartWithin(*model, i, j, false, qa, delta, s, reach, m)) << "trial " << trial;
        const Eigen::Vector3d start = pose * moving.capsule.start, end = pose * moving.capsule.end;
        const detail::BoundingPlane plane =
            detail::capsulesPlane(start, end, moving.capsule.radius, standingPose * standing.capsule.start,
                                  standingPose * standing.capsule.end, standing.capsule.radius);
        const double bounding =
            detail::capsulePlaneReach(start, end, moving.capsule.radius, plane, velocity, curvature, m);
        if (bounding > 0.0) ++bounded;
        ASSERT_TRUE(apartWithin(*model, i, j, false, qa, delta, s, bounding, m)) << "bounding, trial " << trial;
      }
    }
  }
  std::cout << "plane reach, self pairs: " << measured << " part pairs, longer on " << longer << ", bounding planes "
            << bounded << "\n";
  EXPECT_GE(measured, 100);
  EXPECT_GE(bounded, 10);
  EXPECT_GE(longer, measured / 4) << longer << " of " << measured;
}

TEST(PlaneReach, BoundingPlanesSeparateTheirVolumesByTheCheckedBounds) {
  // Random capsules against capsules and against boxes (rotated), apart or not: where a plane is given, every point
  // sampled in the moving capsule lies at least `gap` short of every point of the other volume along its normal, and
  // the gap is the bound the certified check takes (segmentDistance less the radii, capsuleBoxLowerBound).
  std::mt19937_64 random(73);
  std::uniform_real_distribution<double> coordinate(-0.3, 0.3), size(0.01, 0.15);
  int planes = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Vector3d start(coordinate(random), coordinate(random), coordinate(random));
    const Eigen::Vector3d end = start + Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
    const double radius = size(random);
    const Eigen::Vector3d otherStart(coordinate(random), coordinate(random), coordinate(random));
    const Eigen::Vector3d otherEnd =
        otherStart + Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
    const double otherRadius = size(random);
    const detail::BoundingPlane capsules = detail::capsulesPlane(start, end, radius, otherStart, otherEnd, otherRadius);
    EXPECT_TRUE(separates(capsules, detail::segmentDistance(start, end, otherStart, otherEnd) - radius - otherRadius,
                          capsulePoints(start, end, radius, capsules.normal, random),
                          capsulePoints(otherStart, otherEnd, otherRadius, capsules.normal, random)))
        << "capsules, trial " << trial;
    // A box of random size and pose.
    const Eigen::Vector3d half(size(random), size(random), size(random));
    Eigen::Isometry3d box = Eigen::Isometry3d::Identity();
    box.linear() =
        Eigen::AngleAxisd(coordinate(random) * 10.0,
                          Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random)).normalized())
            .toRotationMatrix();
    box.translation() = otherStart;
    const Eigen::Isometry3d toBox = box.inverse();
    const detail::BoundingPlane boxPlane = detail::capsuleBoxPlane(start, end, radius, toBox, half);
    std::vector<Eigen::Vector3d> corners;
    for (int corner = 0; corner < 8; ++corner) {
      corners.push_back(box * Eigen::Vector3d((corner & 1 ? 1 : -1) * half.x(), (corner & 2 ? 1 : -1) * half.y(),
                                              (corner & 4 ? 1 : -1) * half.z()));
    }
    EXPECT_TRUE(separates(boxPlane, detail::capsuleBoxLowerBound(toBox * start, toBox * end, radius, half),
                          capsulePoints(start, end, radius, boxPlane.normal, random), corners))
        << "box, trial " << trial;
    planes += (capsules.gap > 0.0) + (boxPlane.gap > 0.0);
  }
  EXPECT_GE(planes, 200);
}

TEST(PlaneReach, ACapsuleStaysShortOfAPlaneWithinItsReach) {
  // The capsules around the UR10e's parts, each before a plane in a random direction (what stands still beyond it),
  // on 0.35 and 1.5 rad motions: no point of the capsule (its surface sampled, rigid with the part) comes within m of
  // the plane anywhere within the reach.
  const auto model = thesisFree();
  const auto& impl = detail::implementationOf(*model);
  const auto& robot = model->robot();
  constexpr double m = 0.002;
  arcplan::robot::KinematicsData at(robot), along(robot);
  std::mt19937_64 random(79);
  std::normal_distribution<double> gaussian;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const VectorXd q = arcplan::testing::randomJointState(robot, random);
    VectorXd direction(robot.dof());
    for (int j = 0; j < robot.dof(); ++j) direction[j] = gaussian(random);
    const VectorXd delta = (trial % 2 == 0 ? 0.35 : 1.5) * direction.normalized();
    const double s = unit(random);
    const VectorXd qa = q - s * delta;
    arcplan::robot::forwardKinematics(robot, q, at);
    const int i = static_cast<int>(random() % impl.robotParts.size());
    const detail::Part& part = impl.robotParts[i];
    const int link = impl.robotPartLink[i];
    const Eigen::Isometry3d pose = partPose(impl, at, i);
    const Eigen::Vector3d start = pose * part.capsule.start, end = pose * part.capsule.end;
    const Eigen::Vector3d normal = Eigen::Vector3d(gaussian(random), gaussian(random), gaussian(random)).normalized();
    detail::BoundingPlane plane;
    plane.normal = normal;
    plane.gap = m + 0.05 * unit(random);
    const double wall = std::max(normal.dot(start), normal.dot(end)) + part.capsule.radius + plane.gap;
    const double reach = detail::capsulePlaneReach(start, end, part.capsule.radius, plane,
                                                   detail::linkVelocity(robot, impl, part.body, at.linkPoses, delta),
                                                   detail::linkCurvature(impl, part.body, delta.cwiseAbs()), m);
    // Surface points of the capsule in its link's frame.
    std::vector<Eigen::Vector3d> points;
    for (int n = 0; n < 300; ++n) {
      const Eigen::Vector3d offset(gaussian(random), gaussian(random), gaussian(random));
      const Eigen::Vector3d onAxis = part.capsule.start + unit(random) * (part.capsule.end - part.capsule.start);
      points.push_back(part.offset * (onAxis + part.capsule.radius * offset.normalized()));
    }
    const double from = std::max(0.0, s - reach), to = std::min(1.0, s + reach);
    for (int n = 0; n <= 40; ++n) {
      const double t = from + (to - from) * n / 40;
      arcplan::robot::forwardKinematics(robot, qa + t * delta, along);
      for (const Eigen::Vector3d& point : points)
        ASSERT_LE(normal.dot(along.linkPoses[link] * point), wall - m + 1e-9)
            << model->linkNames()[part.body] << " trial " << trial << " at " << t << " of the reach " << reach;
    }
    ++checked;
  }
  EXPECT_EQ(checked, 300);
}

}  // namespace
