// Via points for the arm (planners/src/arm_contact.h): where a link above the tool met a body, the body
// as the TCP sees it, and a beam across the forearm's sweep that the TCP's own line never touches.
#include <gtest/gtest.h>
#include <ompl/base/PlannerStatus.h>

#include <algorithm>
#include <string>
#include <vector>

#include "arm_contact.h"
#include "planners/planner_test_support.h"

namespace {

using namespace arcplan::testing;
using arcplan::planners::ArmContact;
using arcplan::planners::ObstacleCluster;
using arcplan::robot::Vector6;
namespace ob = ompl::base;

TEST(ArmContact, TheBodySeenFromTheTcpIsItsHullMinusEveryLinkPoint) {
  const ObstacleCluster cluster{{"block"}, {{1.0, 0.0, 0.5}, {1.0, 0.2, 0.5}}};
  const std::vector<Eigen::Vector3d> link{{0.0, 0.0, 0.3}, {-0.1, 0.0, 0.4}};
  const ObstacleCluster seen = arcplan::planners::seenFromTheTcp(cluster, link);
  EXPECT_EQ(seen.names, cluster.names);
  ASSERT_EQ(seen.hull.size(), 4u);
  // Where the TCP may not go so that these link points stay off the two hull points.
  for (const Eigen::Vector3d& expected : {Eigen::Vector3d(1.0, 0.0, 0.2), Eigen::Vector3d(1.1, 0.0, 0.1),
                                          Eigen::Vector3d(1.0, 0.2, 0.2), Eigen::Vector3d(1.1, 0.2, 0.1)}) {
    EXPECT_TRUE(std::any_of(seen.hull.begin(), seen.hull.end(), [&](const Eigen::Vector3d& p) {
      return (p - expected).norm() < 1e-12;
    })) << expected.transpose();
  }
}

TEST(ArmContact, NamesTheLinkItsSideAndWhereItIsFromTheTcp) {
  const auto& robot = arcplan::robot::ur10e();
  const auto outlines = arcplan::planners::linkOutlines(robot);
  Vector6 q;
  q << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098;  // thesis start: elbow up, tool down
  arcplan::robot::KinematicsData kinematics(robot);
  arcplan::robot::forwardKinematics(robot, q, kinematics);
  const Eigen::Vector3d elbow = kinematics.linkPoses[robot.linkIndex("forearm_link")].translation();
  const Eigen::Vector3d tcp = kinematics.linkPoses[robot.tipLink()].translation();
  // A ball 15 cm above the elbow: the forearm meets it from below.
  const auto ball = sphere("ball", elbow + Eigen::Vector3d(0.0, 0.0, 0.15), 0.03);
  const std::vector<ArmContact> contacts =
      arcplan::planners::armContacts(robot, outlines, q, {{"forearm_link", "ball"}, {"wrist_3_link", "other"}}, {ball});
  ASSERT_EQ(contacts.size(), 1u);  // "other" is not among the bodies
  const ArmContact& contact = contacts[0];
  EXPECT_EQ(contact.link, "forearm_link");
  // The contact point lies on the forearm (among its outline points, placed by forward kinematics) ...
  const Eigen::Vector3d point = tcp + contact.offset;
  EXPECT_TRUE(std::any_of(contact.outline.begin(), contact.outline.end(),
                          [&](const Eigen::Vector3d& p) { return (p - contact.offset).norm() < 1e-12; }));
  // ... below the ball (the side points down, away from it), far from the TCP (the elbow is ~0.6 m up).
  EXPECT_LT(point.z(), ball.pose.translation().z());
  EXPECT_LT(contact.side.z(), -0.5);
  EXPECT_NEAR(contact.side.norm(), 1.0, 1e-12);
  EXPECT_GT(contact.offset.norm(), 0.3);
  // No forearm point is nearer the ball's bounding cube (side 2 r about its centre) than the contact point.
  const auto cubeDistance = [&](const Eigen::Vector3d& p) {
    return ((p - ball.pose.translation()).cwiseAbs().array() - ball.radius).cwiseMax(0.0).matrix().norm();
  };
  for (const Eigen::Vector3d& p : contact.outline) EXPECT_GE(cubeDistance(tcp + p), cubeDistance(point) - 1e-12);
}

TEST(ArmContact, AContactAtTheToolIsLeftToTheTcpsOwnCandidates) {
  const auto& robot = arcplan::robot::ur10e();
  const auto outlines = arcplan::planners::linkOutlines(robot);
  Vector6 q;
  q << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098;
  arcplan::robot::KinematicsData kinematics(robot);
  arcplan::robot::forwardKinematics(robot, q, kinematics);
  const Eigen::Vector3d tcp = kinematics.linkPoses[robot.tipLink()].translation();
  const auto ball = sphere("ball", tcp + Eigen::Vector3d(0.0, 0.0, -0.05), 0.02);  // just below the flange
  EXPECT_TRUE(arcplan::planners::armContacts(robot, outlines, q, {{"wrist_3_link", "ball"}}, {ball}).empty());
  // Positive control, same configuration and ball: beside wrist 1, farther than kArmContactReach from the
  // TCP (measured here by forward kinematics), the same call names the link.
  const Eigen::Vector3d wrist1 = kinematics.linkPoses[robot.linkIndex("wrist_1_link")].translation();
  ASSERT_GT((wrist1 - tcp).norm(), arcplan::planners::kArmContactReach + 0.05);
  const auto beside = sphere("ball", wrist1 + Eigen::Vector3d(0.0, 0.0, 0.05), 0.02);
  const std::vector<ArmContact> contacts =
      arcplan::planners::armContacts(robot, outlines, q, {{"wrist_1_link", "ball"}}, {beside});
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].link, "wrist_1_link");
  EXPECT_GT(contacts[0].offset.norm(), arcplan::planners::kArmContactReach);
}

// Synthetic postures for the detour searches: a TCP position is "clear" unless it lies in one of these
// boxes (what the IK and the clearance test say of a real arm, here known exactly).
struct BlockedBoxes {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boxes;  // low, high corners
  bool operator()(const Eigen::Vector3d& p) const {
    return std::none_of(boxes.begin(), boxes.end(), [&](const auto& box) {
      return (p.array() >= box.first.array()).all() && (p.array() <= box.second.array()).all();
    });
  }
  // Every point of the polyline, 1 mm apart, is clear (finer than the searches' 2 cm probes).
  bool polylineClear(const std::vector<Eigen::Vector3d>& points) const {
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
      const int steps = static_cast<int>(std::ceil((points[i + 1] - points[i]).norm() / 0.001));
      for (int k = 0; k <= steps; ++k) {
        if (!(*this)(points[i] + (points[i + 1] - points[i]) * (static_cast<double>(k) / steps))) return false;
      }
    }
    return true;
  }
};

// A wall across the leg (0,0,0) -> (1,0,0): x in [0.3, 0.5], |y| < 0.12, z < 0.1; the floor below z = -0.05.
BlockedBoxes wallAcrossTheLeg() {
  return BlockedBoxes{{{{0.3, -0.12, -1.0}, {0.5, 0.12, 0.1 - 1e-9}}, {{-5.0, -5.0, -5.0}, {5.0, 5.0, -0.05}}}};
}

TEST(ArmDetours, TheBlockedSpanIsWhereTheProbesAlongTheLegFail) {
  const BlockedBoxes wall = wallAcrossTheLeg();
  const auto span = arcplan::planners::blockedSpan({0, 0, 0}, {1, 0, 0}, 0.35, wall);
  // Probes 2 cm apart from 0.35: 0.31 is the last blocked one going back (0.29 is clear), 0.49 going on.
  EXPECT_NEAR(span.from, 0.31, 1e-9);
  EXPECT_NEAR(span.to, 0.49, 1e-9);
  // A clear posture at `at` is no span at all.
  const auto none = arcplan::planners::blockedSpan({0, 0, 0}, {1, 0, 0}, 0.7, wall);
  EXPECT_EQ(none.from, 0.7);
  EXPECT_EQ(none.to, 0.7);
}

TEST(ArmDetours, EachPlaneGetsTheSmallestLiftThatClearsTheWall) {
  const BlockedBoxes wall = wallAcrossTheLeg();
  const Eigen::Vector3d p(0, 0, 0), q(1, 0, 0);
  const auto detours = arcplan::planners::clearingDetours(p, q, {0.31, 0.49}, wall);
  ASSERT_FALSE(detours.empty());
  bool over = false, beside = false;
  for (const auto& detour : detours) {
    ASSERT_EQ(detour.points.size(), 2u);
    std::vector<Eigen::Vector3d> polyline{p, detour.points[0], detour.points[1], q};
    EXPECT_TRUE(wall.polylineClear(polyline));
    // Over the wall: z = 0.1 is the lowest clear height, so the lift of the ladder is 0.1 (0.06 below it);
    // entering and leaving one lift before and after the span (45° ramps).
    if (detour.points[0].z() > 0.05 && std::abs(detour.points[0].y()) < 1e-9) {
      over = true;
      EXPECT_TRUE(detour.points[0].isApprox(Eigen::Vector3d(0.21, 0.0, 0.1), 1e-9)) << detour.points[0].transpose();
      EXPECT_TRUE(detour.points[1].isApprox(Eigen::Vector3d(0.59, 0.0, 0.1), 1e-9)) << detour.points[1].transpose();
      EXPECT_NEAR(detour.margin, 0.1 - 0.06, 1e-12);
    }
    // Beside it: |y| must exceed 0.12, the ladder's 0.15.
    if (std::abs(detour.points[0].z()) < 1e-9) {
      beside = true;
      EXPECT_NEAR(std::abs(detour.points[0].y()), 0.15, 1e-9);
      EXPECT_NEAR(detour.points[0].x(), 0.31 - 0.15, 1e-9);
      EXPECT_NEAR(detour.points[1].x(), 0.49 + 0.15, 1e-9);
    }
    // Nothing under it: the floor is 5 cm down and the wall reaches it.
    EXPECT_GT(detour.points[0].z(), -0.05);
  }
  EXPECT_TRUE(over);
  EXPECT_TRUE(beside);
}

TEST(ArmDetours, TheLatticeFindsAWayOverAWallNoSingleLiftClears) {
  // A wall 0.5 m high across everything (no way beside it), its top out of the detours' 45° ramps
  // within the leg: the lattice goes over it.
  const BlockedBoxes wall{{{{0.4, -5.0, -1.0}, {0.6, 5.0, 0.5}}, {{-5.0, -5.0, -5.0}, {5.0, 5.0, -0.05}}}};
  const Eigen::Vector3d p(0, 0, 0), q(1, 0, 0);
  const auto way = arcplan::planners::latticeDetour(p, q, wall, 10);
  ASSERT_TRUE(way.has_value());
  ASSERT_FALSE(way->points.empty());
  EXPECT_LE(way->points.size(), 10u);
  std::vector<Eigen::Vector3d> polyline{p};
  polyline.insert(polyline.end(), way->points.begin(), way->points.end());
  polyline.push_back(q);
  EXPECT_TRUE(wall.polylineClear(polyline));
  double highest = 0.0;
  for (const Eigen::Vector3d& v : way->points) highest = std::max(highest, v.z());
  EXPECT_GT(highest, 0.5);
  // Not much longer than the shortest way over (up to 0.5 m at x = 0.4 and down from x = 0.6).
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i) length += (polyline[i + 1] - polyline[i]).norm();
  const double shortest = std::hypot(0.4, 0.5) + 0.2 + std::hypot(0.4, 0.5);
  EXPECT_GE(length, shortest - 1e-9);
  EXPECT_LT(length, shortest + 0.25);
}

TEST(ArmDetours, TheLatticeGivesUpWhereTheGoalIsWalledIn) {
  // q inside a closed shell of blocked positions: no way in, within the lattice's bounded tests.
  const Eigen::Vector3d q(1, 0, 0);
  BlockedBoxes shell;
  for (int axis = 0; axis < 3; ++axis) {  // two 5 cm slabs per axis (x, y, z), 0.15-0.2 m from q, low side first
    for (const double side : {-1.0, 1.0}) {
      Eigen::Vector3d low = q - Eigen::Vector3d::Constant(0.2), high = q + Eigen::Vector3d::Constant(0.2);
      (side < 0 ? high : low)[axis] = q[axis] + side * 0.15;
      shell.boxes.emplace_back(low, high);
    }
  }
  ASSERT_TRUE(shell(q));
  EXPECT_FALSE(arcplan::planners::latticeDetour({0, 0, 0}, q, shell, 10).has_value());
  // Positive control: the same call with the shell open at +y (not towards p: the way in turns round)
  // finds its way in.
  BlockedBoxes open = shell;
  open.boxes.erase(open.boxes.begin() + 3);
  const auto way = arcplan::planners::latticeDetour({0, 0, 0}, q, open, 10);
  ASSERT_TRUE(way.has_value());
  std::vector<Eigen::Vector3d> polyline{{0, 0, 0}};
  polyline.insert(polyline.end(), way->points.begin(), way->points.end());
  polyline.push_back(q);
  EXPECT_TRUE(open.polylineClear(polyline));
}

// The generated suite's forearm-beam-001 (families of issue 23, seed 20240611): a 0.67 m beam across the
// forearm's sweep, the straight TCP line 1 cm or more from it. Before via points came from the arm's
// contact, the arc planner fell back to joint space here (6.53 s to execute; RRTConnect + simplifier
// 10.67 s).
arcplan::planners::PlanningProblem forearmBeamProblem() {
  auto scene = std::make_shared<arcplan::collision::Scene>(*loadTestScene("thesis_free"));
  auto beam = box("beam", {0.28947437883956, -0.298530511446351, 0.418969094905294},
                  {0.665239600945358, 0.103799047660059, 0.106788037349963});
  beam.pose.linear() = arcplan::robot::rotationFromRpy(0.0, 0.0, 0.224413365259277);
  scene->obstacles.push_back(beam);
  Vector6 start, goal;
  start << -1.35601285627815, -1.43827505095287, 2.64638529739421, -2.77890657323624, -1.5707963267949,
      -1.35601285627815;
  goal << -1.62570568363867, -1.07783720548585, 1.71684140883585, -2.2098005301449, -1.5707963267949, -1.62570568363867;
  scene->queries[0].start = arcplan::collision::QueryEndpoint{std::nullopt, std::nullopt, start};
  scene->queries[0].goal = arcplan::collision::QueryEndpoint{std::nullopt, std::nullopt, goal};
  return arcplan::planners::makePlanningProblem(scene);
}

TEST(ArmContact, ABeamAcrossTheForearmsSweepIsPassedWithLinesAndArcs) {
  auto problem = forearmBeamProblem();
  const auto [planner, status] = solve(problem, "arc", {{"fallback", "0"}});
  const auto& result = arcOf(planner).lastResult();
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << result.reason;
  EXPECT_EQ(result.mode(), "arc");
  EXPECT_FALSE(result.viaPoints.empty());
  EXPECT_NE(std::find(result.obstacles.begin(), result.obstacles.end(), "beam"), result.obstacles.end());
  // The straight line is free for the tool: the beam is at least 1 cm from the TCP's segment A-B.
  const Eigen::Vector3d a = arcplan::robot::tipPose(arcplan::robot::ur10e(), problem.start).translation();
  const Eigen::Vector3d b = arcplan::robot::tipPose(arcplan::robot::ur10e(), problem.goal).translation();
  const auto& beam = problem.scene->obstacles.back();
  for (int k = 0; k <= 100; ++k) {
    const Eigen::Vector3d local = beam.pose.inverse() * Eigen::Vector3d(a + (b - a) * (k / 100.0));
    EXPECT_GT((local.cwiseAbs() - 0.5 * beam.size).cwiseMax(0.0).norm(), 0.01) << k;
  }
  // The path keeps 1 cm everywhere, measured independently of the planner's certified check.
  EXPECT_GE(closestApproach(problem), 0.01 - 1e-6);
}

// The generated suite's forearm-beam-011 (seed 20240611): a beam across the upper arm's and forearm's sweep
// near the base. No via point over, beside or under it clears the arm (the search exhausted its routes and
// fell back to joint space, 6.8 s to execute); the arm passes it low, the TCP near the table.
arcplan::planners::PlanningProblem upperArmBeamProblem() {
  auto scene = std::make_shared<arcplan::collision::Scene>(*loadTestScene("thesis_free"));
  auto beam = box("beam", {0.19865537916383, 0.302090638445797, 0.805541074616536},
                  {0.994337452535656, 0.0475643834102874, 0.115713834109601});
  beam.pose.linear() = arcplan::robot::rotationFromRpy(0.0, 0.0, -1.7523223997636);
  scene->obstacles.push_back(beam);
  Vector6 start, goal;
  start << -0.19061958865577, -0.958818647123847, 1.83534732930038, -2.44732500897143, -1.5707963267949,
      -0.190619588655769;
  goal << 0.783098819597691, -2.008806199887, 2.31271157416581, -1.8747017010737, -1.57079632679489, 0.783098819597691;
  scene->queries[0].start = arcplan::collision::QueryEndpoint{std::nullopt, std::nullopt, start};
  scene->queries[0].goal = arcplan::collision::QueryEndpoint{std::nullopt, std::nullopt, goal};
  return arcplan::planners::makePlanningProblem(scene);
}

TEST(ArmDetours, ABeamNoViaPointClearsIsPassedLowThroughTheArmsClearPostures) {
  auto problem = upperArmBeamProblem();
  const auto [planner, status] = solve(problem, "arc", {{"auto", "1"}, {"fallback", "0"}});
  const auto& result = arcOf(planner).lastResult();
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << result.reason;
  EXPECT_EQ(result.mode(), "arc");
  EXPECT_GT(result.viaPoints.size(), 2u);
  // Passed low: some via point near the table, far below both ends.
  const Eigen::Vector3d a = arcplan::robot::tipPose(arcplan::robot::ur10e(), problem.start).translation();
  const Eigen::Vector3d b = arcplan::robot::tipPose(arcplan::robot::ur10e(), problem.goal).translation();
  double lowest = std::min(a.z(), b.z());
  for (const Eigen::Vector3d& v : result.viaPoints) lowest = std::min(lowest, v.z());
  EXPECT_LT(lowest, std::min(a.z(), b.z()) - 0.05);
  EXPECT_GE(closestApproach(problem), 0.01 - 1e-6);
}

}  // namespace
