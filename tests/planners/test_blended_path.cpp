// Lines through via points with blended corners: lengths and inside distances from the circle
// geometry of a corner, C¹ junctions, sampling, and the blends that fit.
#include <gtest/gtest.h>

#include <cmath>

#include "arcplan/common/error.h"
#include "arcplan/planners/blended_path.h"

namespace {

using arcplan::planners::BlendedPath;
using Eigen::Vector3d;

Eigen::Isometry3d at(const Vector3d& position) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = position;
  return pose;
}

TEST(BlendedPath, RightAngleCornerHasTheQuarterCircleOfItsTangentLength) {
  // Corner of 90°: radius t / tan(45°) = t; the path loses 2t of line and gains a quarter circle.
  const double t = 0.2;
  const BlendedPath path(at({0, 0, 0}), at({1, 1, 0}), {Vector3d(1, 0, 0)}, {t});
  EXPECT_NEAR(path.length(), 2.0 - 2.0 * t + M_PI_2 * t, 1e-12);
  const auto [from, to] = path.blendSpan(0);
  EXPECT_NEAR(from, 1.0 - t, 1e-12);
  EXPECT_NEAR(to - from, M_PI_2 * t, 1e-12);
  // The arc's midpoint passes t·tan(φ/4) inside the corner: t (√2 − 1) for 90°.
  const Vector3d middle = path.position(0.5 * (from + to));
  EXPECT_NEAR((middle - Vector3d(1, 0, 0)).norm(), t * std::tan(M_PI / 8.0), 1e-12);
  EXPECT_NEAR((middle - Vector3d(1 - t, t, 0)).norm(), t, 1e-12);  // on the circle about its centre
}

TEST(BlendedPath, PositionAndTangentAreContinuousAtEveryJunction) {
  const std::vector<Vector3d> vias{Vector3d(0.3, 0.2, 0.4), Vector3d(0.6, 0.1, 0.5), Vector3d(0.8, -0.2, 0.2)};
  const BlendedPath path(at({0, 0, 0.2}), at({1, 0, 0.3}), vias, {0.05, 0.08, 0.1});
  for (std::size_t i = 0; i < vias.size(); ++i) {
    const auto [from, to] = path.blendSpan(i);
    for (const double s : {from, to}) {
      const double h = 1e-7;
      EXPECT_LT((path.position(s + h) - path.position(s - h)).norm(), 3 * h);
      EXPECT_LT((path.tangent(s + h) - path.tangent(s - h)).norm(), 1e-5) << "corner " << i << " at " << s;
      EXPECT_NEAR(path.tangent(s).norm(), 1.0, 1e-12);
    }
    // The blend is tangent to the legs where it meets them: at t from the via point.
    EXPECT_NEAR((path.position(from) - vias[i]).norm(), path.blends()[i], 1e-12);
    EXPECT_NEAR((path.position(to) - vias[i]).norm(), path.blends()[i], 1e-12);
  }
}

TEST(BlendedPath, SamplesKeepTheResolutionAndEndExactlyAtTheGoal) {
  const BlendedPath path(at({0, 0, 0}), at({1, 1, 0}), {Vector3d(1, 0, 0)}, {0.3});
  const auto samples = path.sample(0.01);
  EXPECT_EQ(samples.front().arcLength, 0.0);
  EXPECT_EQ(samples.back().pose.translation(), Vector3d(1, 1, 0));
  EXPECT_NEAR(samples.back().arcLength, path.length(), 1e-12);
  for (std::size_t k = 1; k < samples.size(); ++k) {
    EXPECT_LE(samples[k].arcLength - samples[k - 1].arcLength, 0.01 + 1e-12);
    EXPECT_LE((samples[k].pose.translation() - samples[k - 1].pose.translation()).norm(), 0.01 + 1e-12);
  }
  EXPECT_THROW(path.sample(0.0), arcplan::Error);
}

TEST(BlendedPath, LargestBlendsUseWholeEndLegsAndHalfSharedLegs) {
  const std::vector<Vector3d> points{Vector3d(0, 0, 0), Vector3d(0.4, 0, 0), Vector3d(0.4, 0.2, 0),
                                     Vector3d(1, 0.2, 0)};
  EXPECT_NEAR(BlendedPath::maxBlend(points, 0), 0.1, 1e-12);  // min(0.4 whole, 0.2 / 2)
  EXPECT_NEAR(BlendedPath::maxBlend(points, 1), 0.1, 1e-12);  // min(0.2 / 2, 0.6 whole)
  EXPECT_NEAR(BlendedPath::turningAngle(points, 1), M_PI_2, 1e-12);
  // Both at their largest: the shared leg is used up by the two arcs, no straight piece is left.
  const BlendedPath path(at(points[0]), at(points[3]), {points[1], points[2]}, {0.1, 0.1});
  EXPECT_NEAR(path.blendSpan(1).first, path.blendSpan(0).second, 1e-12);
  EXPECT_THROW(BlendedPath(at(points[0]), at(points[3]), {points[1], points[2]}, {0.15, 0.1}), arcplan::Error);
  EXPECT_THROW(BlendedPath(at(points[0]), at(points[3]), {points[1], points[2]}, {0.0, 0.1}), arcplan::Error);
  EXPECT_THROW(BlendedPath(at(points[0]), at(points[3]), {points[1]}, {0.1, 0.1}), arcplan::Error);
}

TEST(BlendedPath, WithoutViaPointsItIsTheStraightLineAndOrientationIsSlerped) {
  Eigen::Isometry3d start = at({0, 0, 0}), goal = at({0.5, 0, 0});
  goal.linear() = Eigen::AngleAxisd(0.4, Vector3d::UnitZ()).toRotationMatrix();
  const BlendedPath line(start, goal, {}, {});
  EXPECT_NEAR(line.length(), 0.5, 1e-15);
  const Eigen::Isometry3d middle = line.pose(0.25);
  EXPECT_NEAR((middle.translation() - Vector3d(0.25, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(Eigen::AngleAxisd(middle.linear()).angle(), 0.2, 1e-12);
}

}  // namespace
