// Densification of joint paths: bounded joint and TCP steps, original waypoints kept, new waypoints
// on the joint-space segments of sparse paths and on a smooth curve through dense ones, TCP data
// equal to an independent forward kinematics call.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/trajectory/path_densification.h"
#include "straight_line.h"
#include "support/segment_distance.h"

namespace arcplan::trajectory {
namespace {

using arcplan::testing::distanceToSegment;

// A sparse path like an RRTConnect result: 4 waypoints, joint steps up to ~1 rad.
JointPath sparsePath() {
  robot::Vector6 a, m1, m2, b;
  a << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098;
  m1 << -0.6, -1.9, 2.0, -1.5, -1.2, -0.2;
  m2 << 0.1, -1.3, 1.6, -2.2, -1.9, 0.9;
  b << 0.399, -1.624, 2.012, -1.958, -1.571, 0.399;
  return {a, m1, m2, b};
}

TEST(PathDensification, StepsAreBoundedAndWaypointsKept) {
  const auto& model = robot::ur10e();
  const JointPath path = sparsePath();
  const DensificationOptions options{0.02, 0.004};
  const DensePath dense = densifyJointPath(model, path, options);

  ASSERT_EQ(dense.waypoints.size(), dense.tcpPositions.size());
  ASSERT_EQ(dense.waypoints.size(), dense.tcpArcLength.size());
  // A lower bound on the count: the joint-step bound alone needs this many segments.
  std::size_t minimumSegments = 0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    minimumSegments += static_cast<std::size_t>(std::ceil((path[i] - path[i - 1]).cwiseAbs().maxCoeff() / 0.02));
  }
  EXPECT_GE(dense.waypoints.size(), minimumSegments + 1);

  std::size_t nextOriginal = 0, segment = 0;
  robot::KinematicsData kinematics(model);
  for (std::size_t k = 0; k < dense.waypoints.size(); ++k) {
    const robot::Vector6& q = dense.waypoints[k];
    if (nextOriginal < path.size() && q == path[nextOriginal]) {
      segment = nextOriginal;
      ++nextOriginal;
    } else {
      ASSERT_LT(segment + 1, path.size());
      EXPECT_LT(distanceToSegment(q, path[segment], path[segment + 1]), 1e-12)
          << "waypoint " << k << " off its segment";
    }
    robot::forwardKinematics(model, q, kinematics);
    EXPECT_LT((kinematics.linkPoses[model.tipLink()].translation() - dense.tcpPositions[k]).norm(), 1e-12);
    if (k > 0) {
      EXPECT_LE((q - dense.waypoints[k - 1]).cwiseAbs().maxCoeff(), 0.02 + 1e-12) << "joint step at " << k;
      const double chord = (dense.tcpPositions[k] - dense.tcpPositions[k - 1]).norm();
      EXPECT_LE(chord, 0.004 + 1e-12) << "TCP step at " << k;
      EXPECT_NEAR(dense.tcpArcLength[k] - dense.tcpArcLength[k - 1], chord, 1e-12);
    }
  }
  EXPECT_EQ(nextOriginal, path.size()) << "an original waypoint is missing or out of order";
  EXPECT_EQ(dense.tcpArcLength.front(), 0.0);
}

// Largest distance of the dense TCP points from the thesis line A→B.
double largestDistanceFromLine(const DensePath& dense) {
  const Eigen::Vector3d a = testing::thesisPoseA().translation();
  const Eigen::Vector3d direction = (testing::thesisPoseB().translation() - a).normalized();
  double largest = 0.0;
  for (const auto& p : dense.tcpPositions) {
    const Eigen::Vector3d offset = p - a;
    largest = std::max(largest, (offset - offset.dot(direction) * direction).norm());
  }
  return largest;
}

// Largest angle between consecutive joint-space steps of the dense path: corners of the curve.
double largestTurn(const DensePath& dense) {
  double largest = 0.0;
  for (std::size_t k = 2; k < dense.waypoints.size(); ++k) {
    const robot::Vector6 before = (dense.waypoints[k - 1] - dense.waypoints[k - 2]).normalized();
    const robot::Vector6 after = (dense.waypoints[k] - dense.waypoints[k - 1]).normalized();
    largest = std::max(largest, std::acos(std::clamp(before.dot(after), -1.0, 1.0)));
  }
  return largest;
}

TEST(PathDensification, CloseWaypointsAreJoinedSmoothly) {
  // The straight TCP line by IK every ~1 cm (joint steps ~0.03 rad). Straight joint-space chords
  // turn at every original waypoint (a joint-velocity jump when timed); a C¹ curve through the
  // waypoints turns a little at every dense step instead. Both stay on the TCP line within 0.1 mm.
  const auto& model = robot::ur10e();
  const JointPath path = testing::straightLinePath(model, 83);
  DensificationOptions straight;
  straight.smoothWaypointSpacing = 0.0;
  const DensePath chords = densifyJointPath(model, path, straight);
  const DensePath smooth = densifyJointPath(model, path);
  EXPECT_LT(largestTurn(smooth), 0.5 * largestTurn(chords));
  EXPECT_LT(largestDistanceFromLine(smooth), 1e-4);
  EXPECT_LT(largestDistanceFromLine(chords), 1e-4);
  // Original waypoints kept, new ones inside the joint box of their segment.
  std::size_t next = 0;
  for (const auto& q : smooth.waypoints) {
    if (next < path.size() && q == path[next]) {
      ++next;
      continue;
    }
    ASSERT_GT(next, 0u);
    const robot::Vector6 low = path[next - 1].cwiseMin(path[next]), high = path[next - 1].cwiseMax(path[next]);
    EXPECT_TRUE((q.array() >= low.array() - 1e-12).all() && (q.array() <= high.array() + 1e-12).all());
  }
  EXPECT_EQ(next, path.size());
}

TEST(PathDensification, ShortSegmentsBesideALongOneFollowTheirOwnRun) {
  // A long joint motion (an RRTConnect edge of an arc fallback path) turning into three short collinear segments
  // (a TCP line's first samples): the short segments are one run, and a curve through collinear points parameterised
  // by joint distance is their straight line, so every dense waypoint of the run lies on the segment from its first
  // to its last waypoint (geometry, independent of the curve's slopes). A curve through the whole path took its
  // slope at the turn from the long motion too and left that line by 2.1e-3 rad.
  const auto& model = robot::ur10e();
  robot::Vector6 start, turn, direction;
  start << -1.2, -1.9, 2.2, -2.4, -1.5, 0.1;
  turn << 0.6, -1.4, 1.5, -1.6, -1.1, 0.8;
  direction << 0.3, -0.5, 0.4, 0.6, -0.2, 0.3;
  direction.normalize();
  const JointPath path{start, turn, turn + 0.03 * direction, turn + 0.06 * direction, turn + 0.09 * direction};
  const DensePath dense = densifyJointPath(model, path);
  // Original waypoints are kept: the run's dense waypoints are the ones after `turn`.
  const auto at = std::find(dense.waypoints.begin(), dense.waypoints.end(), turn);
  ASSERT_NE(at, dense.waypoints.end());
  double largest = 0.0;
  int inRun = 0;
  for (auto q = std::next(at); q != dense.waypoints.end(); ++q, ++inRun)
    largest = std::max(largest, distanceToSegment(*q, turn, path.back()));
  EXPECT_GE(inRun, 9);  // 0.09 rad at 0.01 rad steps
  EXPECT_LT(largest, 1e-12);
}

TEST(PathDensification, TcpLengthConvergesAsStepsShrink) {
  // The chord sum of a finer resampling is longer (a chord is never longer than the arc) and the
  // difference shrinks quadratically with the step.
  const auto& model = robot::ur10e();
  const double coarse = densifyJointPath(model, sparsePath(), {0.05, 0.02}).tcpArcLength.back();
  const double fine = densifyJointPath(model, sparsePath(), {0.01, 0.002}).tcpArcLength.back();
  const double finest = densifyJointPath(model, sparsePath(), {0.005, 0.001}).tcpArcLength.back();
  EXPECT_LT(coarse, fine);
  EXPECT_LT(fine, finest);
  EXPECT_LT(finest - fine, 0.5 * (fine - coarse));
}

TEST(PathDensification, RepeatedWaypointsAreDropped) {
  const auto& model = robot::ur10e();
  JointPath path = sparsePath();
  path.insert(path.begin() + 2, path[1]);
  const DensePath withRepeat = densifyJointPath(model, path);
  const DensePath without = densifyJointPath(model, sparsePath());
  EXPECT_EQ(withRepeat.waypoints.size(), without.waypoints.size());
  for (std::size_t k = 1; k < withRepeat.waypoints.size(); ++k) {
    EXPECT_GT((withRepeat.waypoints[k] - withRepeat.waypoints[k - 1]).norm(), 0.0);
  }
}

TEST(PathDensification, DensePathIsKeptAsIs) {
  const auto& model = robot::ur10e();
  JointPath path;
  for (int i = 0; i <= 50; ++i) path.push_back(sparsePath()[0] + 0.0001 * i * robot::Vector6::Ones());
  EXPECT_EQ(densifyJointPath(model, path).waypoints.size(), path.size());
}

TEST(PathDensification, BadInput) {
  const auto& model = robot::ur10e();
  EXPECT_THROW(densifyJointPath(model, sparsePath(), {0.0, 0.002}), Error);
  EXPECT_THROW(densifyJointPath(model, sparsePath(), {0.01, -1.0}), Error);
  EXPECT_THROW(densifyJointPath(model, sparsePath(), {0.01, 0.002, -0.1}), Error);
  EXPECT_THROW(densifyJointPath(model, {sparsePath()[0]}), Error);
  try {
    densifyJointPath(model, {sparsePath()[0], sparsePath()[0]});
    FAIL() << "a path without motion was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("same configuration"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace arcplan::trajectory
