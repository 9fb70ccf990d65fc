// PathValidator: a walk's certifier never carries over to the next walk (a failed route or detour
// candidate followed by a valid one), the one-configuration test behind the route probes, and the screen
// that refuses a path where its certified walk would stop, without certifying anything.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/planners/arc_path.h"
#include "path_validation.h"
#include "planners/planner_test_support.h"
#include "support/held_balls.h"

namespace {

using namespace arcplan::testing;
using arcplan::planners::ArcPath;
using arcplan::planners::ConversionStatus;
using arcplan::planners::PathValidator;
using arcplan::testing::HeldBalls;

constexpr double kMargin = 0.01;

PathValidator certifyingValidator(const arcplan::planners::PlanningProblem& problem,
                                  const arcplan::robot::UrInverseKinematics& ik) {
  return PathValidator(
      *problem.collisionModel, ik, {}, kMargin, true, [](const arcplan::robot::Vector6&) { return true; },
      [] { return false; });
}

arcplan::planners::JointConversionResult startOnly(const arcplan::robot::Vector6& start) {
  arcplan::planners::JointConversionResult prefix;
  prefix.joints.push_back(start);
  prefix.arcLengths.push_back(0.0);
  return prefix;
}

// The thesis' detour with h = 0.5 r around the particle from a to b (valid: thesis regression).
ArcPath thesisDetour(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const double o = 0.375 * (b.translation() - a.translation()).norm();
  return ArcPath(a, b, {{o, {0.1, 0.2, 0.1, 0.2}, 0.0}});
}

TEST(PathValidation, AFailedWalkDoesNotAffectTheNextOne) {
  auto problem = thesisProblem("thesis_obstacle");
  const arcplan::robot::UrInverseKinematics ik(arcplan::robot::ur10e());
  const Eigen::Isometry3d a = tcpPoses({problem.start})[0], b = tcpPoses({problem.goal})[0];
  // The detour, and the straight line through the particle (invalid).
  const ArcPath detour = thesisDetour(a, b);
  const ArcPath line(a, b);

  PathValidator fresh = certifyingValidator(problem, ik);
  const auto alone = fresh.walk(detour, startOnly(problem.start), problem.goal).waypoints;
  ASSERT_TRUE(alone.ok()) << alone.reason;

  PathValidator reused = certifyingValidator(problem, ik);
  const auto failed = reused.walk(line, startOnly(problem.start), problem.goal);
  ASSERT_EQ(failed.waypoints.status, ConversionStatus::Rejected);
  ASSERT_TRUE(failed.rejected);
  EXPECT_TRUE(reused.explain(*failed.rejected).involves("particle"));
  const auto after = reused.walk(detour, startOnly(problem.start), problem.goal).waypoints;
  ASSERT_TRUE(after.ok()) << after.reason;
  // The same waypoints as a validator that never saw the failure, and the margin really kept.
  ASSERT_EQ(after.joints.size(), alone.joints.size());
  for (std::size_t i = 0; i < alone.joints.size(); ++i) EXPECT_EQ(after.joints[i], alone.joints[i]) << "waypoint " << i;
  EXPECT_GE(closestApproach(problem, after.joints), kMargin - 1e-6);
}

// A walk given the conversion its screen left (nothing refused) is the walk that converts the path itself; a screen
// that refuses the path leaves no conversion (the walk is not needed, and the path was converted only up to there).
TEST(PathValidation, AWalkGivenItsScreensConversionIsTheWalkThatConvertsThePath) {
  auto problem = thesisProblem("thesis_obstacle");
  const arcplan::robot::UrInverseKinematics ik(arcplan::robot::ur10e());
  const Eigen::Isometry3d a = tcpPoses({problem.start})[0], b = tcpPoses({problem.goal})[0];
  const ArcPath detour = thesisDetour(a, b);
  PathValidator screened = certifyingValidator(problem, ik), alone = certifyingValidator(problem, ik);
  arcplan::planners::JointConversionResult converted;
  ASSERT_FALSE(screened.screen(detour, startOnly(problem.start), problem.goal, &converted));
  ASSERT_GT(converted.joints.size(), 2u);
  const auto given = screened.walk(detour, startOnly(problem.start), problem.goal, &converted).waypoints;
  const auto own = alone.walk(detour, startOnly(problem.start), problem.goal).waypoints;
  ASSERT_TRUE(own.ok()) << own.reason;
  EXPECT_EQ(given.status, own.status) << given.reason;
  EXPECT_EQ(given.joints, own.joints);
  EXPECT_EQ(given.arcLengths, own.arcLengths);
  arcplan::planners::JointConversionResult throughTheParticle;
  EXPECT_TRUE(screened.screen(ArcPath(a, b), startOnly(problem.start), problem.goal, &throughTheParticle));
  EXPECT_TRUE(throughTheParticle.joints.empty());
}

TEST(PathValidation, KeepsMarginTestsOneConfigurationAndExplainsARejection) {
  auto problem = thesisProblem("thesis_obstacle");
  const arcplan::robot::UrInverseKinematics ik(arcplan::robot::ur10e());
  PathValidator validator = certifyingValidator(problem, ik);
  arcplan::collision::CollisionData data(*problem.collisionModel);
  EXPECT_TRUE(validator.keepsMargin(problem.start));
  // The tool at the particle (on the line, 0.375 of the way from A): in contact.
  const Eigen::Isometry3d a = tcpPoses({problem.start})[0], b = tcpPoses({problem.goal})[0];
  Eigen::Isometry3d atParticle = a;
  atParticle.translation() = a.translation() + 0.375 * (b.translation() - a.translation());
  const auto q = ik.solveBranch(atParticle, ik.branchOf(problem.start), problem.start[5]);
  ASSERT_TRUE(q);
  ASSERT_LT(arcplan::collision::distance(*problem.collisionModel, data, *q).minimum(), kMargin);
  EXPECT_FALSE(validator.keepsMargin(*q));
  const auto rejection = validator.explain({*q, *q});
  EXPECT_TRUE(rejection.involves("particle"));
  // 3 cm above the start: farther than the margin from everything (checked independently).
  Eigen::Isometry3d lifted = a;
  lifted.translation().z() += 0.03;
  const auto free = ik.solveBranch(lifted, ik.branchOf(problem.start), problem.start[5]);
  ASSERT_TRUE(free);
  ASSERT_GE(arcplan::collision::distance(*problem.collisionModel, data, *free).minimum(), kMargin);
  EXPECT_TRUE(validator.keepsMargin(*free));
}

TEST(PathValidation, TheScreenRefusesAPathWhereItsWalkStopsWithoutCertifyingIt) {
  auto problem = thesisProblem("thesis_obstacle");
  const arcplan::robot::UrInverseKinematics ik(arcplan::robot::ur10e());
  const Eigen::Isometry3d a = tcpPoses({problem.start})[0], b = tcpPoses({problem.goal})[0];
  const ArcPath line(a, b);  // through the particle
  // Independently: the line's waypoints (IK only) and their distances; the first closer than the margin, and the
  // first of the waypoints before it that all keep less than the margin plus the certificate's acceptance margin
  // (min(m/4, 0.5 mm), motion_check.h).
  const auto converted = arcplan::planners::convertToJoints(ik, line, problem.start, problem.goal, {}, 0.0,
                                                            std::numeric_limits<double>::infinity(), {});
  arcplan::collision::CollisionData data(*problem.collisionModel);
  const auto distanceAt = [&](std::size_t k) {
    return arcplan::collision::distance(*problem.collisionModel, data, converted.joints[k]).minimum();
  };
  std::size_t refused = 1;
  while (refused < converted.joints.size() && distanceAt(refused) >= kMargin) ++refused;
  ASSERT_LT(refused, converted.joints.size());
  std::size_t approach = refused;
  while (approach > 1 && distanceAt(approach - 1) < kMargin + 0.0005) --approach;

  PathValidator validator = certifyingValidator(problem, ik);
  const auto screened = validator.screen(line, startOnly(problem.start), problem.goal);
  ASSERT_TRUE(screened);
  EXPECT_EQ(screened->waypoints.status, ConversionStatus::Rejected);
  EXPECT_DOUBLE_EQ(screened->waypoints.failedAtArcLength, converted.arcLengths[approach]);
  ASSERT_TRUE(screened->rejected);
  EXPECT_EQ(screened->rejected->to, converted.joints[approach]);
  EXPECT_EQ(screened->waypoints.joints.size(), 1u) << "nothing after the prefix is certified";
  EXPECT_TRUE(validator.explain(*screened->rejected).involves("particle"));
  // The certified walk stops at the same waypoint.
  const auto walked = validator.walk(line, startOnly(problem.start), problem.goal);
  EXPECT_EQ(walked.waypoints.status, ConversionStatus::Rejected);
  EXPECT_DOUBLE_EQ(walked.waypoints.failedAtArcLength, converted.arcLengths[approach]);

  // A path that keeps the margin (the thesis detour, valid by the thesis regression) passes the screen: the walk
  // decides.
  const ArcPath detour = thesisDetour(a, b);
  EXPECT_FALSE(validator.screen(detour, startOnly(problem.start), problem.goal));
  EXPECT_TRUE(validator.walk(detour, startOnly(problem.start), problem.goal).ok());
}

TEST(PathValidation, ARejectionEndingWithinTheAcceptanceMarginIsExplainedByThePairThere) {
  auto problem = thesisProblem("thesis_obstacle");
  const arcplan::robot::UrInverseKinematics ik(arcplan::robot::ur10e());
  arcplan::collision::CollisionData data(*problem.collisionModel);
  const Eigen::Isometry3d a = tcpPoses({problem.start})[0], b = tcpPoses({problem.goal})[0];
  const auto onTheLine = [&](double fraction) {
    Eigen::Isometry3d pose = a;
    pose.translation() = a.translation() + fraction * (b.translation() - a.translation());
    return *ik.solveBranch(pose, ik.branchOf(problem.start), problem.start[5]);
  };
  const auto distanceAt = [&](const arcplan::robot::Vector6& q) {
    return arcplan::collision::distance(*problem.collisionModel, data, q).minimum();
  };
  // The tool at the particle (0.375 of the way, in contact), and a configuration on the way there whose distance
  // lies between the margin and the margin plus the certificate's acceptance margin (0.5 mm at 1 cm), by bisection.
  const arcplan::robot::Vector6 inContact = onTheLine(0.375);
  ASSERT_LE(distanceAt(inContact), 0.0);
  double low = 0.0, high = 0.375;  // distance above the band at low, below it at high
  arcplan::robot::Vector6 band = onTheLine(low);
  for (int k = 0; k < 60 && !(distanceAt(band) >= kMargin + 1e-4 && distanceAt(band) < kMargin + 4e-4); ++k) {
    const double middle = 0.5 * (low + high);
    band = onTheLine(middle);
    (distanceAt(band) >= kMargin + 2.5e-4 ? low : high) = middle;
  }
  ASSERT_GE(distanceAt(band), kMargin + 1e-4);
  ASSERT_LT(distanceAt(band), kMargin + 4e-4);
  // A motion from the contact to it: the certificate refuses the pair at its end, which names the reason (the states
  // along the motion, the first of them in contact, are not asked).
  PathValidator validator = certifyingValidator(problem, ik);
  const auto rejection = validator.explain({inContact, band});
  EXPECT_FALSE(rejection.collides);
  EXPECT_DOUBLE_EQ(rejection.closest, distanceAt(band));
  EXPECT_TRUE(rejection.involves("particle"));
}

// The screen goes back from the waypoint it refuses only while the waypoints are within the acceptance margin: an
// earlier place where the path came that close and left again is not where the walk is refused. The thesis detour
// (h = 0.05) driven from B to A passes the particle twice: 3.78 cm from it, then farther than 4.2 cm, then into
// it. With a margin of 3.77 cm the first pass lies within the margin plus 0.5 mm (distances measured
// independently below).
TEST(PathValidation, TheScreenGoesBackFromTheRefusedWaypointOnlyWhileWithinTheMargin) {
  auto problem = thesisProblem("thesis_obstacle");
  const arcplan::robot::UrInverseKinematics ik(arcplan::robot::ur10e());
  const Eigen::Isometry3d a = tcpPoses({problem.start})[0], b = tcpPoses({problem.goal})[0];
  const double length = (b.translation() - a.translation()).norm();
  const ArcPath twice(b, a, {{0.625 * length, {0.05, 0.1, 0.05, 0.1}, 0.0}});
  constexpr double kDipMargin = 0.0377, kBand = kDipMargin + 0.0005;  // + min(m/4, 0.5 mm), motion_check.h
  const auto converted = arcplan::planners::convertToJoints(ik, twice, problem.goal, problem.start, {}, 0.0,
                                                            std::numeric_limits<double>::infinity(), {});
  arcplan::collision::CollisionData data(*problem.collisionModel);
  std::vector<double> d;
  for (const auto& q : converted.joints)
    d.push_back(arcplan::collision::distance(*problem.collisionModel, data, q).minimum());
  std::size_t refused = 1;
  while (refused < d.size() && d[refused] >= kDipMargin) ++refused;
  ASSERT_LT(refused, d.size());
  std::size_t approach = refused;
  while (approach > 1 && d[approach - 1] < kBand) --approach;
  // The profile the case needs: within the band earlier, out of it between.
  std::size_t earlier = 1;
  while (earlier < approach && d[earlier] >= kBand) ++earlier;
  ASSERT_LT(earlier + 1, approach) << "the path comes within the margin before it leaves it again";

  PathValidator validator(
      *problem.collisionModel, ik, {}, kDipMargin, true, [](const arcplan::robot::Vector6&) { return true; },
      [] { return false; });
  const auto screened = validator.screen(twice, startOnly(problem.goal), problem.start);
  ASSERT_TRUE(screened) << "refused at the second pass";
  EXPECT_EQ(screened->waypoints.status, ConversionStatus::Rejected);
  EXPECT_DOUBLE_EQ(screened->waypoints.failedAtArcLength, converted.arcLengths[approach]);
  ASSERT_TRUE(screened->rejected);
  EXPECT_EQ(screened->rejected->to, converted.joints[approach]);

  // With a margin of 3.85 cm the first pass already comes closer than the margin (3.78 cm, between two waypoints
  // the stride tests, which keep 3.85-3.9 cm): every walk stops there. The screen must not place the rejection at
  // the second pass (where going back from a refused waypoint would): it leaves the walk to decide or names the
  // first pass.
  constexpr double kDeeperMargin = 0.0385;
  std::size_t firstBelow = 1;
  while (firstBelow < d.size() && d[firstBelow] >= kDeeperMargin) ++firstBelow;
  std::size_t out = firstBelow;
  while (out < d.size() && d[out] < kDeeperMargin + 0.0005) ++out;
  ASSERT_LT(out, d.size()) << "the path leaves the margin after the first pass";
  ASSERT_LT(*std::min_element(d.begin() + static_cast<long>(out), d.end()), kDeeperMargin) << "and comes back";
  PathValidator deeper(
      *problem.collisionModel, ik, {}, kDeeperMargin, true, [](const arcplan::robot::Vector6&) { return true; },
      [] { return false; });
  const auto walked = deeper.walk(twice, startOnly(problem.goal), problem.start);
  EXPECT_EQ(walked.waypoints.status, ConversionStatus::Rejected);
  EXPECT_LE(walked.waypoints.failedAtArcLength, converted.arcLengths[firstBelow]);
  const auto deeperScreen = deeper.screen(twice, startOnly(problem.goal), problem.start);
  EXPECT_TRUE(!deeperScreen || deeperScreen->waypoints.failedAtArcLength <= converted.arcLengths[firstBelow])
      << deeperScreen->waypoints.failedAtArcLength << " m";
}

// The stop request (the planner's termination condition) ends a screen as it ends a walk.
TEST(PathValidation, TheScreenHonoursTheStopRequest) {
  auto problem = thesisProblem("thesis_obstacle");
  const arcplan::robot::UrInverseKinematics ik(arcplan::robot::ur10e());
  const ArcPath line(tcpPoses({problem.start})[0], tcpPoses({problem.goal})[0]);  // through the particle
  PathValidator stopped(
      *problem.collisionModel, ik, {}, kMargin, true, [](const arcplan::robot::Vector6&) { return true; },
      [] { return true; });
  EXPECT_FALSE(stopped.screen(line, startOnly(problem.start), problem.goal));
  EXPECT_EQ(stopped.walk(line, startOnly(problem.start), problem.goal).waypoints.status, ConversionStatus::Rejected);
  PathValidator running = certifyingValidator(problem, ik);
  EXPECT_TRUE(running.screen(line, startOnly(problem.start), problem.goal)) << "refused without the stop request";
}

// The screen and the explanations ask each pair what a certificate accepts of it: its own m (a self pair's at most
// 1 mm, docs/collision.md#clearance) plus the acceptance margin. Two balls held by the arm (tests/support/held_balls.h,
// their distance from forward kinematics): at 1.1 mm they meet a 1 cm clearance, but a 1 cm walk may stop there
// (1 mm + 0.25 mm); at 2 mm it may not; at 0.5 mm no walk starts, and the balls are named as the reason.
TEST(PathValidation, ASelfPairIsJudgedByWhatTheCertificateAcceptsOfIt) {
  const HeldBalls balls;
  const auto model = arcplan::collision::makeCollisionModel(balls.scene());
  const arcplan::robot::UrInverseKinematics ik(model->robot());
  PathValidator validator(
      *model, ik, {}, kMargin, true, [](const arcplan::robot::Vector6&) { return true; }, [] { return false; });
  arcplan::collision::CollisionData data(*model);
  const arcplan::robot::Vector6 within = balls.at(balls.angleWhere(0.0011, +1) - HeldBalls::kWristStep);
  const arcplan::robot::Vector6 clear = balls.at(balls.angleWhere(0.002, -1));
  const arcplan::robot::Vector6 touching = balls.at(balls.angleWhere(0.0005, +1));
  for (const auto& q : {within, clear, touching}) {
    const auto report = arcplan::collision::distance(*model, data, q);
    ASSERT_EQ(report.selfPair, (arcplan::collision::NamePair{"ball_a", "ball_b"}));
    ASSERT_NEAR(report.selfDistance, balls.gap(q[4]), 1e-6);
    ASSERT_GE(report.obstacleDistance, 0.02);
  }
  ASSERT_GT(balls.gap(within[4]), 0.001);
  ASSERT_LT(balls.gap(within[4]), 0.00125);
  ASSERT_GE(balls.gap(clear[4]), 0.002);
  ASSERT_LT(balls.gap(touching[4]), 0.0005);
  ASSERT_TRUE(arcplan::collision::hasClearance(*model, data, within, kMargin));  // the rule: met
  EXPECT_TRUE(validator.withinMargin(within));
  EXPECT_TRUE(validator.keepsMargin(within));  // a walk may start there: the pair keeps its 1 mm
  EXPECT_FALSE(validator.withinMargin(clear));
  EXPECT_TRUE(validator.keepsMargin(clear));
  EXPECT_FALSE(validator.keepsMargin(touching));
  for (const auto& q : {within, touching}) {
    const auto rejection = validator.explain({q, q});
    EXPECT_FALSE(rejection.collides);
    EXPECT_TRUE(rejection.involves("ball_a") && rejection.involves("ball_b"));
    EXPECT_NEAR(rejection.closest, balls.gap(q[4]), 1e-6);
  }
}

}  // namespace
