// The bound along a kept separating direction (separatingGap, docs/collision.md "A separating direction kept per part
// pair") for the convex parts of arcplan's UR10e against box, cylinder and sphere obstacles: the primitives' support
// functions are closed-form, and the direction comes from the exact GJK distance (partsDistance keeps it). Compared
// with FCL's own GJK distance of the same two shapes.
#include <cmath>
#include <random>
#include <string>

#include <fcl/narrowphase/distance.h>
#include <gtest/gtest.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/common/resources.h"
#include "model_implementation.h"  // collision/src
#include "support/separating_direction.h"

namespace {

using namespace arcplan::collision;

double fclDistance(const detail::Part& a, const Eigen::Isometry3d& poseA, const detail::Part& b,
                   const Eigen::Isometry3d& poseB) {
  static const fcl::DistanceRequestd request(false, false, 0.0, 0.0, 1e-9);
  fcl::DistanceResultd result;
  return fcl::distance(a.convexGeometry.get(), poseA, b.convexGeometry.get(), poseB, request, result);
}

// Each convex link part of the UR10e at random orientations 0-8 cm beside a box, a cylinder and a sphere: along the
// direction partsDistance kept, the bound is within 10 um of FCL's distance for nearly every pose and never above it;
// along any direction it is never above it (a support function too small would put it there; one too large would
// leave it loose along GJK's own direction).
TEST(SeparatingDirections, ThePrimitivesSupportFunctionsBoundTheDistanceFromBelowAndTightly) {
  const auto model = makeCollisionModel(loadScene(arcplan::dataDirectory() / "scenes" / "thesis_free.yaml"));
  const auto& impl = detail::implementationOf(*model);
  const CollisionModelOptions& options = model->options();
  const detail::Part obstacles[] = {detail::boxPart(Eigen::Vector3d(0.3, 0.12, 0.05)),
                                    detail::cylinderPart(0.05, 0.2, options.distanceBoundingVolume),
                                    detail::spherePart(0.06, options.distanceBoundingVolume)};
  std::mt19937_64 random(31);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int parts = 0, measured = 0, tight = 0;
  for (const detail::Part& part : impl.robotParts) {
    if (!part.convexGeometry || part.convexGeometry->getNodeType() != fcl::GEOM_CONVEX) continue;
    ++parts;
    const double reach = (part.capsule.end - part.capsule.start).norm() / 2.0 + part.capsule.radius;
    for (int k = 0; k < 12; ++k) {
      const detail::Part& obstacle = obstacles[k % 3];
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity(), obstaclePose = Eigen::Isometry3d::Identity();
      pose.linear() = Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random)).normalized().matrix();
      obstaclePose.linear() =
          Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random)).normalized().matrix();
      // The part's centre in a random direction from the obstacle's centre, about as far as both reach.
      const Eigen::Vector3d away = Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
      const Eigen::Vector3d centre = pose * ((part.capsule.start + part.capsule.end) / 2.0);
      pose.translation() += (reach + 0.1 + 0.08 * unit(random)) * away - centre;
      const double exact = fclDistance(part, pose, obstacle, obstaclePose);
      if (!(exact > 1e-4)) continue;  // touching: no direction
      SCOPED_TRACE("part " + std::to_string(parts) + " pose " + std::to_string(k));
      Eigen::Vector3d axis = Eigen::Vector3d::Zero();
      const double d = detail::partsDistance(part, pose, obstacle, obstaclePose, false, options, &axis);
      ASSERT_NEAR(d, exact, 1e-9);
      const Eigen::Vector3d any = Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
      tight += arcplan::testing::separatingDirectionHolds(part, pose, obstacle, obstaclePose, axis, any, exact);
      ++measured;
    }
  }
  EXPECT_GT(parts, 5);
  EXPECT_GT(measured, parts * 8);
  EXPECT_GT(tight, measured * 9 / 10) << tight << " of " << measured;
}

}  // namespace
