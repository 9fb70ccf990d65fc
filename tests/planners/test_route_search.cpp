// The lazy route search: shortest route first, failed legs pruned from every route, bounded depth.
#include <gtest/gtest.h>

#include <cmath>

#include "route_search.h"

namespace {

using namespace arcplan::planners;
using Eigen::Vector3d;

const Vector3d kStart(0, 0, 0), kGoal(1, 0, 0);

TEST(RouteSearch, ShortestRouteFirstAndFailedLegsArePruned) {
  RouteSearch search(kStart, kGoal, 4);
  const auto straight = search.next();
  ASSERT_TRUE(straight.has_value());
  EXPECT_EQ(straight->points.size(), 2u);
  EXPECT_NEAR(straight->length, 1.0, 1e-15);
  const Vector3d high(0.5, 0.0, 0.3), low(0.5, 0.0, 0.1), side1(0.3, 0.2, 0.0), side2(0.7, 0.2, 0.0);
  search.legFailed(*straight, 0, {{{high}, 0.1}, {{low}, 0.02}, {{side1, side2}, 0.05}});
  // Lengths: low 2·√(0.25 + 0.01) = 1.0198, side 2·√(0.09 + 0.04) + 0.4 = 1.1211, high 2·√(0.34) = 1.1662.
  const auto first = search.next();
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->points[1], low);
  EXPECT_NEAR(first->length, 2.0 * std::sqrt(0.26), 1e-12);
  EXPECT_EQ(first->margins, std::vector<double>{0.02});
  // The low route's first leg fails with no way round it: the side route comes next.
  search.removeLeg(*first, 0);
  const auto second = search.next();
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->points.size(), 4u);
  EXPECT_EQ(second->margins, (std::vector<double>{0.05, 0.05}));
  // Its middle leg fails and gets a way round; the high route (shorter) is taken before the deeper one.
  search.legFailed(*second, 1, {{{Vector3d(0.5, 0.5, 0.0)}, 0.1}});
  const auto third = search.next();
  ASSERT_TRUE(third.has_value());
  EXPECT_EQ(third->points[1], high);
  const auto fourth = search.next();
  ASSERT_TRUE(fourth.has_value());
  EXPECT_EQ(fourth->points.size(), 5u);
  EXPECT_EQ(fourth->points[2], Vector3d(0.5, 0.5, 0.0));
  EXPECT_FALSE(search.next().has_value());
  EXPECT_EQ(search.routesTried(), 5u);
}

TEST(RouteSearch, RoutesStopGrowingAtTheViaPointBound) {
  RouteSearch search(kStart, kGoal, 1);
  const auto straight = search.next();
  search.legFailed(*straight, 0,
                   {{{Vector3d(0.5, 0, 0.2)}, 0.02}, {{Vector3d(0.3, 0, 0.2), Vector3d(0.7, 0, 0.2)}, 0.02}});
  const auto single = search.next();
  ASSERT_TRUE(single.has_value());
  EXPECT_EQ(single->points.size(), 3u);
  search.legFailed(*single, 0, {{{Vector3d(0.2, 0, 0.3)}, 0.02}});
  EXPECT_FALSE(search.next().has_value());
}

TEST(RouteSearch, TowardChordStopsOnTheSegmentBetweenTheNeighbours) {
  const Vector3d prev(0, 0, 0), next(2, 0, 0), via(1, 1, 0);
  EXPECT_TRUE(towardChord(prev, via, next, 0.5).isApprox(Vector3d(1, 0.5, 0), 1e-15));
  EXPECT_TRUE(towardChord(prev, via, next, 3.0).isApprox(Vector3d(1, 0, 0), 1e-15));  // not past the chord
  // Beyond the segment's end the nearest point is that end: (3, 1) moves along (-1, -1)/√2.
  const Vector3d moved = towardChord(prev, Vector3d(3, 1, 0), next, std::sqrt(0.5));
  EXPECT_TRUE(moved.isApprox(Vector3d(2.5, 0.5, 0), 1e-15));
}

// The start (0,0,0) and goal (1,0,0) with a ball of radius 0.1 at (0.5,0,0) between them and a clearance of
// 1 cm: a path is valid where all of it keeps 0.11 m from the centre (checked every 0.5 mm).
const Vector3d kBallCentre(0.5, 0, 0);
constexpr double kKeptDistance = 0.11;

double closestApproach(const BlendedPath& path) {
  double closest = std::numeric_limits<double>::infinity();
  const int samples = static_cast<int>(std::ceil(path.length() / 0.0005));
  for (int k = 0; k <= samples; ++k)
    closest = std::min(closest, (path.position(path.length() * k / samples) - kBallCentre).norm());
  return closest;
}

// The shortest way round the ball in a plane through the line: tangent, arc of the kept radius, tangent.
double shortestWayRound() {
  const double d = 0.5, r = kKeptDistance;
  return 2.0 * std::sqrt(d * d - r * r) + r * (M_PI - 2.0 * std::acos(r / d));
}

TEST(RouteSearch, ShorteningNeverLengthensAndKeepsTheClearance) {
  const Eigen::Isometry3d start{Eigen::Translation3d(kStart)}, goal{Eigen::Translation3d(kGoal)};
  const auto keepsClearance = [](const BlendedPath& path) { return closestApproach(path) >= kKeptDistance; };
  // An apex 22 cm above the smallest that clears the ball with straight legs (0.1128 m), and an over pair.
  const std::vector<std::pair<std::vector<Vector3d>, std::vector<double>>> routes = {
      {{Vector3d(0.5, 0, 0.3328)}, {0.22}},
      {{Vector3d(0.35, 0, 0.31), Vector3d(0.65, 0, 0.31)}, {0.2, 0.2}},
      {{Vector3d(0.5, 0.1, 0.2)}, {0.05}},
  };
  for (const auto& [vias, margins] : routes) {
    std::vector<double> blends;
    for (std::size_t i = 0; i < vias.size(); ++i) blends.push_back(0.05);
    const BlendedPath validated(start, goal, vias, blends);
    ASSERT_TRUE(keepsClearance(validated));
    int calls = 0;
    RouteShortening shortening(start, goal, validated, margins, 8);
    while (const auto candidate = shortening.next()) {
      ++calls;
      shortening.accept(keepsClearance(*candidate));
    }
    const BlendedPath& shortened = shortening.best();
    EXPECT_LE(calls, 8);
    EXPECT_LT(shortened.length(), validated.length() - 0.01) << vias.size() << " via points";
    EXPECT_GE(shortened.length(), shortestWayRound());
    EXPECT_GE(closestApproach(shortened), kKeptDistance);
    EXPECT_TRUE(shortened.points().front().isApprox(kStart) && shortened.points().back().isApprox(kGoal));
  }
  // Nothing validates: the route is returned as it was.
  const BlendedPath validated(start, goal, {Vector3d(0.5, 0, 0.3328)}, {0.05});
  RouteShortening refusing(start, goal, validated, {0.22}, 8);
  while (refusing.next()) refusing.accept(false);
  const BlendedPath& unchanged = refusing.best();
  EXPECT_EQ(unchanged.points(), validated.points());
  EXPECT_EQ(unchanged.length(), validated.length());
}

}  // namespace
