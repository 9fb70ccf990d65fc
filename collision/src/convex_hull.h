#pragma once
// The convex hull of a point set as an FCL convex shape (qhull), made to contain every point: the
// layer between a part's bounding capsule and its exact mesh (docs/collision.md, "Layers"). A hull
// that does not touch an obstacle proves the mesh inside it free, and its distance is a lower bound
// of the mesh's, at the cost of a GJK query instead of a BVH traversal of thousands of triangles.
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <fcl/geometry/shape/convex.h>

namespace arcplan::collision::detail {

// The hull of `points` (at least 4 not coplanar), pushed out so that every point lies inside or on
// it (qhull's facets may leave a point outside by rounding). Null when the points span no volume.
// The vertices' and faces' vectors are also returned through the shape (fcl::Convexd::getVertices).
std::shared_ptr<fcl::Convexd> containingHull(const std::vector<Eigen::Vector3d>& points);

// Largest signed distance of a point outside the convex shape's face planes (<= 0: all inside).
double largestOutside(const fcl::Convexd& hull, const std::vector<Eigen::Vector3d>& points);

}  // namespace arcplan::collision::detail
