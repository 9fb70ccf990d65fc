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
  const Eigen::Vector3d tcp = arcplan::robot::tipPose(robot, q).translation();
  const auto ball = sphere("ball", tcp + Eigen::Vector3d(0.0, 0.0, -0.05), 0.02);  // just below the flange
  EXPECT_TRUE(arcplan::planners::armContacts(robot, outlines, q, {{"wrist_3_link", "ball"}}, {ball}).empty());
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

}  // namespace
