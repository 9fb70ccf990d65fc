// The lazy route search: shortest route first, failed legs pruned from every route, bounded depth.
#include <gtest/gtest.h>

#include "arcplan/planners/route_search.h"

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
  search.legFailed(*straight, 0, {{{Vector3d(0.5, 0, 0.2)}, 0.02}, {{Vector3d(0.3, 0, 0.2), Vector3d(0.7, 0, 0.2)}, 0.02}});
  const auto single = search.next();
  ASSERT_TRUE(single.has_value());
  EXPECT_EQ(single->points.size(), 3u);
  search.legFailed(*single, 0, {{{Vector3d(0.2, 0, 0.3)}, 0.02}});
  EXPECT_FALSE(search.next().has_value());
}

}  // namespace
