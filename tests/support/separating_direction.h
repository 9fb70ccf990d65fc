#pragma once
// What a separating direction kept for a part pair promises (collision/src: detail::separatingGap), checked against
// the pair's distance measured otherwise (`exact`, FCL's): the bound along the unit direction `axis` is never above
// it, nor along any other unit direction `any`. Returns whether the bound along `axis` is tight (within 10 µm).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "model_implementation.h"  // collision/src

namespace arcplan::testing {

inline bool separatingDirectionHolds(const collision::detail::Part& a, const Eigen::Isometry3d& poseA,
                                     const collision::detail::Part& b, const Eigen::Isometry3d& poseB,
                                     const Eigen::Vector3d& axis, const Eigen::Vector3d& any, double exact) {
  EXPECT_NEAR(axis.norm(), 1.0, 1e-12);
  const double along = collision::detail::separatingGap(a, poseA, b, poseB, axis);
  EXPECT_LE(along, exact + 1e-6);
  EXPECT_LE(collision::detail::separatingGap(a, poseA, b, poseB, any), exact + 1e-6);
  return along >= exact - 1e-5;
}

}  // namespace arcplan::testing
