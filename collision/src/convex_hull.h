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

// A hull with fewer vertices that still contains every point: the hull of the points extreme along
// `directions` evenly spread directions, scaled about its centre to contain the rest. Its GJK queries
// cost a fraction of the full hull's on parts with thousands of hull vertices (the MBM FTS300 and
// Robotiq meshes), at a bound a few millimetres looser. Null when those points span no volume.
std::shared_ptr<fcl::Convexd> coarseContainingHull(const std::vector<Eigen::Vector3d>& points, int directions);

// The points extreme along `directions` evenly spread directions (a Fibonacci lattice on the sphere), each
// once: the corners of coarseContainingHull, and a part's witness points (parts.h).
std::vector<Eigen::Vector3d> extremePoints(const std::vector<Eigen::Vector3d>& points, int directions);

// The centroid of a point set and its principal axes: the eigenvectors of the points' covariance (columns, in
// increasing order of spread, `spread` their eigenvalues). Capsules, sphere slabs and sphere groups are laid
// along these axes, and a set whose smallest spread vanishes spans no volume.
struct PrincipalAxes {
  Eigen::Vector3d centroid;
  Eigen::Matrix3d axes;
  Eigen::Vector3d spread;
};
PrincipalAxes principalAxes(const std::vector<Eigen::Vector3d>& points);

// Largest signed distance of a point outside the convex shape's face planes (<= 0: all inside).
double largestOutside(const fcl::Convexd& hull, const std::vector<Eigen::Vector3d>& points);

}  // namespace arcplan::collision::detail
