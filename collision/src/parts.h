#pragma once
// Internal building blocks of CollisionModel: a "part" is one convex-ish piece of a body (a closed
// component of a link mesh, a URDF primitive, an obstacle) with its FCL geometries, a conservative
// bounding volume for the broad phase and a solid description for containment tests.
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <fcl/geometry/collision_geometry.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/robot/mesh.h"

namespace arcplan::collision::detail {

struct Capsule {
  Eigen::Vector3d start = Eigen::Vector3d::Zero(), end = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

// What containment tests know about a part's volume (in the part frame).
struct Solid {
  enum class Kind { None, Convex, ClosedMesh, Sphere, Box, Cylinder };
  Kind kind = Kind::None;
  std::vector<Eigen::Vector4d> planes;  // Convex: inside ⇔ n·x <= d for every (n, d)
  robot::TriangleMesh mesh;             // ClosedMesh: outward triangles
  double radius = 0.0, halfLength = 0.0;
  Eigen::Vector3d halfExtents = Eigen::Vector3d::Zero();

  bool contains(const Eigen::Vector3d& point) const;
};

struct Part {
  int body = -1;
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();  // part frame in the body frame (world for obstacles)
  std::shared_ptr<fcl::CollisionGeometryd> collisionGeometry, distanceGeometry;
  // The part as one convex FCL shape (fcl::Convex of a closed convex component, or the primitive)
  // for GJK queries, which also see a part lying entirely inside the other; null otherwise.
  std::shared_ptr<fcl::CollisionGeometryd> convexGeometry;
  // A convex shape containing the part: convexGeometry where there is one, else the convex hull of
  // a mesh part's vertices (convex_hull.h). Its GJK answers are bounds between the capsule and the
  // exact mesh: no contact proves the part free, its distance is a lower bound of the part's.
  std::shared_ptr<fcl::CollisionGeometryd> hullGeometry;
  // Where the hull has many vertices: a containing hull with few (convex_hull.h coarseContainingHull),
  // asked first — its bounds are looser but its GJK queries much cheaper. Null otherwise.
  std::shared_ptr<fcl::CollisionGeometryd> coarseHullGeometry;
  // Cylinders and spheres only: a convex triangle mesh containing the primitive (containing_meshes.h), as a
  // BVH of the distance queries' type, and its solid (Convex). Against a mesh part its distance is a lower
  // bound of the primitive's, found with triangle distances instead of a GJK per triangle. Null otherwise.
  std::shared_ptr<fcl::CollisionGeometryd> containingMesh;
  Solid containingSolid;
  int triangleCount = 0;  // mesh parts: what FCL's exact queries against a primitive cost grows with
  // Broad phase: a capsule in the part frame, or (obstacle boxes) the box itself.
  bool boxBound = false;
  Capsule capsule;
  Eigen::Vector3d boxHalfExtents = Eigen::Vector3d::Zero();
  Solid solid;
  Eigen::Vector3d referencePoint = Eigen::Vector3d::Zero();  // a point of the part, in the part frame
  // Points whose convex hull contains the part, in the part frame (mesh vertices, box corners;
  // empty for spheres and cylinders, whose capsule stands in): the farthest point of the part from
  // anything is one of them, which is what motion bounds need.
  std::vector<Eigen::Vector3d> hullPoints;
  // A few points of the part itself, in the part frame (mesh vertices extreme along fixed directions, box
  // corners; empty for spheres and cylinders): a witness closer to an obstacle than a required distance proves
  // the part closer too, without an exact distance (witnessCloser, model_implementation.h).
  std::vector<Eigen::Vector3d> witnessPoints;
};

// One part per closed component of the mesh (edge-connected triangles after welding identical
// vertices); meshes with very many components become a single part.
std::vector<Part> meshParts(const robot::TriangleMesh& mesh, const CollisionModelOptions& options);
// Primitives; `containingMesh` is built with the given BVH type (CollisionModelOptions::distanceBoundingVolume).
// A box has none: FCL's mesh–box distance costs as much as the box's own 12 triangles would.
Part spherePart(double radius, BoundingVolume containingMesh);
Part boxPart(const Eigen::Vector3d& size);
Part cylinderPart(double radius, double length, BoundingVolume containingMesh);

// A capsule containing all the given capsules (fitted to their end points, radius grown by the largest radius).
Capsule enclosingCapsule(const std::vector<Capsule>& capsules);

// The closest points of the segments [p0, p1] and [q0, q1] (first on [p0, p1]), and their distance.
std::pair<Eigen::Vector3d, Eigen::Vector3d> segmentClosestPoints(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                                 const Eigen::Vector3d& q0, const Eigen::Vector3d& q1);
double segmentDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                       const Eigen::Vector3d& q1);

// Per axis of a box centred at the origin (half extents given), how far a capsule's bounding box (end points, radius,
// in the box frame) lies beyond the box's faces (> 0: apart along that axis), and whether beyond the upper face.
struct CapsuleBoxGaps {
  Eigen::Vector3d gap;
  Eigen::Matrix<bool, 3, 1> aboveUpperFace;
};
CapsuleBoxGaps capsuleBoxGaps(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius,
                              const Eigen::Vector3d& halfExtents);

// A lower bound of the distance between a capsule (end points, radius, in the box frame) and a box
// centred at the origin with the given half extents: the gap between the capsule's bounding box and
// the box (capsuleBoxGaps). <= 0 means the bounding volumes overlap.
double capsuleBoxLowerBound(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius,
                            const Eigen::Vector3d& halfExtents);

}  // namespace arcplan::collision::detail
