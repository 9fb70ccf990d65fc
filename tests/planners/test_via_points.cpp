// Obstacle clusters and the via-point candidates around them, against the geometry of simple bodies.
#include <gtest/gtest.h>

#include <cmath>

#include "support/obstacles.h"
#include "support/segment_distance.h"
#include "via_points.h"

namespace {

using arcplan::collision::Obstacle;
using namespace arcplan::planners;
using arcplan::testing::box;
using arcplan::testing::distanceToSegment;
using arcplan::testing::sphere;
using Eigen::Vector3d;

TEST(ViaPoints, HullPointsContainTheBody) {
  Obstacle rotated = box("box", Vector3d(0.5, 0.1, 0.3), Vector3d(0.2, 0.1, 0.06));
  rotated.pose.linear() = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const auto corners = hullPoints(rotated);
  ASSERT_EQ(corners.size(), 8u);
  for (const Vector3d& c : corners)
    EXPECT_NEAR((c - rotated.pose.translation()).norm(), rotated.boundingRadius(), 1e-12);
  Obstacle cylinder;
  cylinder.shape = Obstacle::Shape::Cylinder;
  cylinder.radius = 0.05;
  cylinder.length = 0.4;
  // Every point of the circle is inside the circumscribed octagon: its support in any horizontal
  // direction is at least the radius.
  const auto rim = hullPoints(cylinder);
  for (double angle = 0.0; angle < 2 * M_PI; angle += 0.1) {
    const Vector3d direction(std::cos(angle), std::sin(angle), 0.0);
    double support = -1.0;
    for (const Vector3d& p : rim) support = std::max(support, p.dot(direction));
    EXPECT_GE(support, 0.05 - 1e-12);
  }
}

TEST(ViaPoints, TouchingBodiesFormOneClusterAndTheTableIsFloor) {
  const std::vector<Obstacle> obstacles{
      box("table", Vector3d(0, 0, -0.025), Vector3d(2, 2, 0.05)),
      box("left", Vector3d(0.6, 0.2, 0.3), Vector3d(0.3, 0.02, 0.6)),
      sphere("far", Vector3d(-0.5, -0.5, 0.4), 0.03),
      box("right", Vector3d(0.6, -0.2, 0.3), Vector3d(0.3, 0.02, 0.6)),
      box("top", Vector3d(0.6, 0.0, 0.6), Vector3d(0.3, 0.42, 0.02)),  // bridges left and right
  };
  const auto clusters = clusterObstacles(obstacles, 0.1);
  ASSERT_EQ(clusters.size(), 2u);
  EXPECT_EQ(clusters[0].names, (std::vector<std::string>{"left", "right", "top"}));
  EXPECT_EQ(clusters[1].names, (std::vector<std::string>{"far"}));
  EXPECT_EQ(clusters[0].hull.size(), 24u);
}

TEST(ViaPoints, CandidatesPassTheBodyWithClearanceAndMargin) {
  const Vector3d p(0.3, -0.4, 0.3), q(0.5, 0.4, 0.3), center = 0.5 * (p + q);
  const double radius = 0.05, clearance = 0.01;
  const auto clusters = clusterObstacles({sphere("ball", center, radius)}, 0.1);
  ASSERT_EQ(clusters.size(), 1u);
  const auto candidates = viaCandidates(clusters[0], p, q, clearance);
  ASSERT_GE(candidates.size(), 100u);  // 12 planes x 5 margins x (over + apex)
  bool liftsStraightUp = false;
  for (const ViaCandidate& candidate : candidates) {
    std::vector<Vector3d> polyline{p};
    polyline.insert(polyline.end(), candidate.points.begin(), candidate.points.end());
    polyline.push_back(q);
    double closest = INFINITY;
    for (std::size_t k = 0; k + 1 < polyline.size(); ++k) {
      closest = std::min(closest, distanceToSegment(center, polyline[k], polyline[k + 1]));
    }
    EXPECT_GE(closest, radius + clearance) << candidate.points.size() << " via points, margin " << candidate.margin;
    // The horizontal leg's "over" candidate in the plane of world up: at the cube's top + clearance + margin.
    if (candidate.points.size() == 2 &&
        std::abs(candidate.points[0].z() - (0.3 + radius + clearance + candidate.margin)) < 1e-12) {
      liftsStraightUp = true;
    }
  }
  EXPECT_TRUE(liftsStraightUp);
}

}  // namespace
