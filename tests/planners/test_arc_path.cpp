// The arc detour geometry against the thesis (Table 3.1, the lengths of Table 3.3 / docs/planners.md)
// and against properties any correct construction must have (C¹ junctions, clearance, lengths).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "arcplan/common/error.h"
#include "arcplan/planners/arc_path.h"
#include "support/error_message.h"

namespace {

using arcplan::testing::errorMessageOf;

using arcplan::planners::ArcParameters;
using arcplan::planners::ArcPath;
using arcplan::planners::Detour;
using arcplan::planners::makeArcDetourProfile;

const Eigen::Vector3d kA(0.4, -0.4, 0.25);
const Eigen::Vector3d kB(0.5, 0.4, 0.46);

// Tool straight down (rpy 0, -pi, pi/2), as in the thesis.
Eigen::Isometry3d toolDownAt(const Eigen::Vector3d& position) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() << 0, -1, 0, -1, 0, 0, 0, 0, -1;
  pose.translation() = position;
  return pose;
}

// O on the line A→B at y = -0.1 (thesis §3.6): its distance from A.
double thesisObstacleDistance() { return (kB - kA).norm() * (-0.1 - kA.y()) / (kB.y() - kA.y()); }

ArcParameters thesisShape(double sagittaFactor) {
  const double r = 0.2;
  return {sagittaFactor * r, r, 0.5 * r, r};
}

ArcPath thesisPath(double sagittaFactor, double planeAngle = 0.0) {
  return ArcPath(toolDownAt(kA), toolDownAt(kB),
                 {Detour{thesisObstacleDistance(), thesisShape(sagittaFactor), planeAngle}});
}

// Expected length written out independently of the library: the main circle passes through (±r, 0)
// and (0, h); a side circle of radius R sits at height R and touches the main circle from outside,
// so its centre is R + Rs from the main centre. The side arc turns by the angle between the
// vertical and the line of centres, the main arc by the sum of both side angles.
double expectedLength(double h, double r, double r2, double r3, double straight) {
  const double rs = (h * h + r * r) / (2.0 * h);
  const double centreDepth = rs - h;
  double total = straight;
  double mainTurn = 0.0;
  for (const double radius : {r2, r3}) {
    const double centreDistance = radius + rs;
    const double verticalGap = radius + centreDepth;
    const double horizontal = std::sqrt(centreDistance * centreDistance - verticalGap * verticalGap);
    const double turn = std::atan2(horizontal, verticalGap);
    total += radius * turn - horizontal;
    mainTurn += turn;
  }
  return total + rs * mainTurn;
}

double polylineLength(const std::vector<arcplan::planners::PathSample>& samples) {
  double length = 0.0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    length += (samples[i].pose.translation() - samples[i - 1].pose.translation()).norm();
  }
  return length;
}

TEST(ArcPath, StraightLengthIsThesisCaseA) {
  const ArcPath straight(toolDownAt(kA), toolDownAt(kB));
  EXPECT_NEAR(straight.length(), 0.8331, 5e-5);
  EXPECT_NEAR(straight.length(), std::sqrt(0.1 * 0.1 + 0.8 * 0.8 + 0.21 * 0.21), 1e-12);
  EXPECT_EQ(straight.junctions().size(), 2u);
}

TEST(ArcPath, AnalyticLengthsMatchDesignReferenceValues) {
  const double straight = (kB - kA).norm();
  const struct {
    double factor;
    double designValue;
  } cases[] = {{1.00, 0.9920}, {0.75, 0.9321}, {0.50, 0.8825}};
  for (const auto& c : cases) {
    const ArcPath path = thesisPath(c.factor);
    EXPECT_NEAR(path.length(), c.designValue, 5e-5) << "h = " << c.factor << " r";
    EXPECT_NEAR(path.length(), expectedLength(c.factor * 0.2, 0.2, 0.1, 0.2, straight), 1e-12);
  }
}

TEST(ArcPath, ProfileMatchesTable31ClosedForms) {
  // h = r: the main arc is the semicircle of radius r about O (zs = 0).
  const auto semicircle = makeArcDetourProfile({0.2, 0.2, 0.1, 0.2});
  EXPECT_NEAR(semicircle.mainRadius, 0.2, 1e-15);
  EXPECT_NEAR(semicircle.mainCenterDepth, 0.0, 1e-15);
  EXPECT_NEAR(semicircle.entryOffset, std::sqrt(0.3 * 0.3 - 0.1 * 0.1), 1e-15);
  EXPECT_NEAR(semicircle.entryAngle, std::acos(1.0 / 3.0), 1e-15);
  EXPECT_NEAR(semicircle.exitOffset, std::sqrt(0.4 * 0.4 - 0.2 * 0.2), 1e-15);
  EXPECT_NEAR(semicircle.exitAngle, M_PI / 3.0, 1e-15);
  // Junction points are where the circles touch: on the line through their centres.
  const auto profile = makeArcDetourProfile({0.05, 0.2, 0.1, 0.2});
  for (int i = 0; i < 2; ++i) {
    const auto& a = profile.arcs[i];
    const auto& b = profile.arcs[i + 1];
    EXPECT_LT((a.point(1.0) - b.point(0.0)).norm(), 1e-14);
    EXPECT_NEAR((a.center - b.center).norm(), a.radius + b.radius, 1e-14);
  }
}

TEST(ArcPath, PositionsAndUnitTangentsAreContinuousAtEveryJunction) {
  for (const double planeAngle : {0.0, 0.7, -2.0}) {
    const ArcPath path = thesisPath(0.5, planeAngle);
    const auto junctions = path.junctions();
    ASSERT_EQ(junctions.size(), 6u);  // A, entry, arc2|arc1, arc1|arc3, exit, B
    const double step = 1e-7;
    for (std::size_t j = 1; j + 1 < junctions.size(); ++j) {
      const double s = junctions[j];
      const Eigen::Vector3d before = path.position(s - step), after = path.position(s + step);
      EXPECT_LT((after - before).norm(), 2.0 * step + 1e-12) << "junction " << j;
      const Eigen::Vector3d tangentBefore = path.tangent(s - step), tangentAfter = path.tangent(s + step);
      EXPECT_NEAR(tangentBefore.norm(), 1.0, 1e-12);
      // Tangent change over 2·step on a radius >= 0.1 m is at most 2e-6 if the tangent is continuous.
      EXPECT_LT((tangentAfter - tangentBefore).norm(), 3e-6) << "junction " << j;
      // Tangent agrees with the finite-difference direction of motion.
      EXPECT_LT(((after - before) / (2.0 * step) - tangentAfter).norm(), 1e-5);
    }
  }
}

TEST(ArcPath, ApexClearanceIsSagittaAndNoPointComesCloserToO) {
  for (const double factor : {1.0, 0.75, 0.5, 0.3}) {
    const double h = factor * 0.2;
    const ArcPath path = thesisPath(factor);
    const Eigen::Vector3d o = kA + thesisObstacleDistance() * (kB - kA).normalized();
    const Eigen::Vector3d up = arcplan::planners::avoidanceDirection(path.lineDirection(), 0.0);
    const auto junctions = path.junctions();
    double highest = 0.0;
    // Main arc: between junctions 2 and 3.
    for (int k = 0; k <= 20000; ++k) {
      const double s = junctions[2] + (junctions[3] - junctions[2]) * k / 20000.0;
      const Eigen::Vector3d p = path.position(s);
      EXPECT_GE((p - o).norm(), h - 1e-12);
      highest = std::max(highest, (p - o).dot(up));
    }
    EXPECT_NEAR(highest, h, 1e-9) << "h = " << factor << " r";
    // The rest of the path keeps at least h as well.
    for (const auto& sample : path.sample(0.002)) EXPECT_GE((sample.pose.translation() - o).norm(), h - 1e-12);
  }
}

TEST(ArcPath, DefaultPlaneIsWorldUpAndPlaneAngleRotatesAboutTheLine) {
  const Eigen::Vector3d direction = (kB - kA).normalized();
  const Eigen::Vector3d up = arcplan::planners::avoidanceDirection(direction, 0.0);
  EXPECT_NEAR(up.dot(direction), 0.0, 1e-15);
  EXPECT_NEAR(up.norm(), 1.0, 1e-15);
  EXPECT_GT(up.z(), 0.9);  // the line rises only 0.21 m over 0.8 m
  const Eigen::Vector3d expectedUp = (Eigen::Vector3d::UnitZ() - direction.z() * direction).normalized();
  EXPECT_LT((up - expectedUp).norm(), 1e-15);
  const Eigen::Vector3d rotated = arcplan::planners::avoidanceDirection(direction, M_PI_2);
  EXPECT_NEAR(rotated.dot(up), 0.0, 1e-15);
  EXPECT_LT((rotated - direction.cross(up)).norm(), 1e-15);

  // The apex moves with the plane: h along the rotated direction.
  const ArcPath path = thesisPath(1.0, M_PI_2);
  const auto junctions = path.junctions();
  const auto profile = makeArcDetourProfile(thesisShape(1.0));
  const double apexFraction = profile.entryAngle / (profile.entryAngle + profile.exitAngle);
  const double apexArcLength = junctions[2] + (junctions[3] - junctions[2]) * apexFraction;
  const Eigen::Vector3d o = kA + thesisObstacleDistance() * direction;
  EXPECT_LT((path.position(apexArcLength) - (o + 0.2 * rotated)).norm(), 1e-12);
}

TEST(ArcPath, VerticalLineUsesWorldXAsUp) {
  const Eigen::Vector3d a(0.5, 0.1, 0.2), b(0.5, 0.1, 0.8);
  const ArcPath path(toolDownAt(a), toolDownAt(b), {Detour{0.3, {0.1, 0.1, 0.05, 0.05}, 0.0}});
  const Eigen::Vector3d away = arcplan::planners::avoidanceDirection(Eigen::Vector3d::UnitZ(), 0.0);
  EXPECT_LT((away - Eigen::Vector3d::UnitX()).norm(), 1e-15);
  double highest = 0.0;
  for (const auto& sample : path.sample(0.001)) {
    highest = std::max(highest, sample.pose.translation().x() - 0.5);
    EXPECT_NEAR(sample.pose.translation().y(), 0.1, 1e-12);
  }
  EXPECT_NEAR(highest, 0.1, 2e-6);  // sampled at 1 mm on radius 0.1: sag <= 1.25e-6
  EXPECT_NEAR(path.length(), expectedLength(0.1, 0.1, 0.05, 0.05, 0.6), 1e-12);
}

TEST(ArcPath, SamplesIncludeEveryJunctionAndRespectTheResolution) {
  const ArcPath path = thesisPath(0.75);
  const double resolution = 0.013;
  const auto samples = path.sample(resolution);
  EXPECT_LT((samples.front().pose.translation() - kA).norm(), 1e-15);
  EXPECT_LT((samples.back().pose.translation() - kB).norm(), 1e-15);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    EXPECT_GT(samples[i].arcLength, samples[i - 1].arcLength);
    EXPECT_LE(samples[i].arcLength - samples[i - 1].arcLength, resolution + 1e-12);
  }
  for (const double junction : path.junctions()) {
    bool found = false;
    for (const auto& sample : samples) {
      if (std::abs(sample.arcLength - junction) < 1e-12 && sample.junction) {
        found = (sample.pose.translation() - path.position(junction)).norm() < 1e-12;
      }
    }
    EXPECT_TRUE(found) << "junction at s = " << junction;
  }
}

TEST(ArcPath, SampledLengthConvergesToAnalyticLength) {
  for (const double factor : {1.0, 0.75, 0.5}) {
    const ArcPath path = thesisPath(factor);
    double previousError = 1.0;
    for (const double resolution : {0.04, 0.01, 0.0025, 0.000625}) {
      const double error = path.length() - polylineLength(path.sample(resolution));
      EXPECT_GE(error, -1e-12);  // a polyline through points of an arc is never longer
      EXPECT_LT(error, previousError);
      previousError = error;
    }
    // Chord error of an arc of radius R at step d is about d²/(24 R²) per unit length.
    EXPECT_LT(previousError / path.length(), 1e-6) << "h = " << factor << " r";
  }
}

TEST(ArcPath, ToolOrientationConstantOrSlerped) {
  const ArcPath constant = thesisPath(0.5);
  for (const auto& sample : constant.sample(0.01)) {
    EXPECT_LT((sample.pose.linear() - toolDownAt(kA).linear()).norm(), 1e-15);
  }
  Eigen::Isometry3d goal = toolDownAt(kB);
  goal.linear() = Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ()) * goal.linear();
  const ArcPath turning(toolDownAt(kA), goal, {Detour{thesisObstacleDistance(), thesisShape(0.5), 0.0}});
  const auto samples = turning.sample(0.01);
  EXPECT_LT((samples.back().pose.linear() - goal.linear()).norm(), 1e-12);
  for (const auto& sample : samples) {
    // Rotation about the common tool axis grows in proportion to the arc length.
    const Eigen::AngleAxisd relative(toolDownAt(kA).linear().transpose() * sample.pose.linear());
    EXPECT_NEAR(std::abs(relative.angle()), 0.8 * sample.arcLength / turning.length(), 1e-9);
  }
}

TEST(ArcPath, ChainedDetoursAddTheirExtraLengths) {
  const double straight = (kB - kA).norm();
  const ArcParameters small{0.05, 0.08, 0.04, 0.04};
  const ArcPath path(toolDownAt(kA), toolDownAt(kB), {Detour{0.2, small, 0.0}, Detour{0.6, small, 1.0}});
  const double single = expectedLength(0.05, 0.08, 0.04, 0.04, straight) - straight;
  EXPECT_NEAR(path.length(), straight + 2.0 * single, 1e-12);
  EXPECT_EQ(path.junctions().size(), 10u);
}

TEST(ArcPath, InvalidParametersAreRejectedWithTheirName) {
  EXPECT_NE(errorMessageOf([] {
              makeArcDetourProfile({0.3, 0.2, 0.1, 0.2});
            }).find("h <= half_chord"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([] { makeArcDetourProfile({0.0, 0.2, 0.1, 0.2}); }).find("sagitta"), std::string::npos);
  EXPECT_NE(errorMessageOf([] {
              makeArcDetourProfile({0.1, 0.2, -0.1, 0.2});
            }).find("entry_radius"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([] { makeArcDetourProfile({0.1, 0.2, 0.1, NAN}); }).find("exit_radius"), std::string::npos);
  EXPECT_NE(errorMessageOf([] { makeArcDetourProfile({0.1, -1.0, 0.1, 0.1}); }).find("half_chord"), std::string::npos);
}

TEST(ArcPath, DetourMustFitBetweenAAndB) {
  // bx2 = 0.283 m for h = r = 0.2, R2 = 0.1: O closer than that to A cannot work.
  const std::string entry = errorMessageOf([] {
    ArcPath(toolDownAt(kA), toolDownAt(kB), {Detour{0.25, thesisShape(1.0), 0.0}});
  });
  EXPECT_NE(entry.find("bx2"), std::string::npos) << entry;
  EXPECT_NE(entry.find("|AO|"), std::string::npos) << entry;
  const std::string exit = errorMessageOf([] {
    ArcPath(toolDownAt(kA), toolDownAt(kB), {Detour{0.6, thesisShape(1.0), 0.0}});
  });
  EXPECT_NE(exit.find("|OB|"), std::string::npos) << exit;
  const std::string overlap = errorMessageOf([] {
    const ArcParameters small{0.05, 0.08, 0.04, 0.04};
    ArcPath(toolDownAt(kA), toolDownAt(kB), {Detour{0.3, small, 0.0}, Detour{0.35, small, 0.0}});
  });
  EXPECT_NE(overlap.find("previous detour"), std::string::npos) << overlap;
  const std::string zero = errorMessageOf([] {
    ArcPath(toolDownAt(kA), toolDownAt(kA), {Detour{0.0, thesisShape(1.0), 0.0}});
  });
  EXPECT_NE(zero.find("|AB| = 0"), std::string::npos) << zero;
  EXPECT_NE(errorMessageOf([] { thesisPath(0.5).sample(0.0); }).find("resolution"), std::string::npos);
}

}  // namespace
