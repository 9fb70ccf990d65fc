#pragma once
// Distance from a point to a straight segment, for tests that check how far a body or a configuration
// lies from a line (TCP lines in Cartesian space, motions in joint space): the closest point's
// parameter is clamped to the segment.
#include <algorithm>
#include <type_traits>

#include <Eigen/Core>

namespace arcplan::testing {

// The segment's ends fix Vector; p converts to it (e.g. an Isometry3d's translation()).
template <typename Vector>
double distanceToSegment(const std::common_type_t<Vector>& p, const Vector& a, const Vector& b) {
  const Vector ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

}  // namespace arcplan::testing
