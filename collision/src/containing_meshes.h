#pragma once
// Triangle meshes that contain a curved primitive (cylinder, sphere): a cheaper stand-in for the primitive
// against a non-convex mesh part. FCL measures a mesh against a curved shape with one GJK per triangle
// pair it cannot prune (MBM's Robotiq finger tips against a grasped can: 1-3 ms); against a triangle mesh
// it uses analytic triangle distances (~50-100 µs). The distance to the containing mesh is a lower bound
// of the distance to the primitive, at most `largestGap` below it.
#include "arcplan/robot/mesh.h"

#include <Eigen/Core>

namespace arcplan::collision::detail {

struct ContainingMesh {
  robot::TriangleMesh mesh;  // convex, outward triangles, in the primitive's frame
  // The farthest any point of the mesh's solid lies from the primitive [m].
  double largestGap = 0.0;
};

// Sides per cylinder cap polygon and subdivisions of the sphere's icosahedron: 32 sides leave a gap of
// r·(1/cos(π/32) − 1) ≈ 0.0048 r (0.15 mm on a 3 cm can), which costs no more than 16 or 64 per query.
inline constexpr int kCylinderSides = 32;
inline constexpr int kSphereSubdivisions = 2;

// Mesh parts with fewer triangles are measured exactly at once: FCL's GJKs against the primitive cost less
// than the containing mesh's bound there (RRTConnect's recorded MBM checks: ~4 µs per exact distance below
// 300 triangles vs ~50 µs for the bound; 2.6-3.5 ms vs 0.13-0.26 ms for the 1776-triangle finger tips).
inline constexpr int kContainingMeshMinTriangles = 1000;

// A prism over a regular polygon circumscribed about the cylinder's caps (vertices at r / cos(π/n)),
// the cylinder's axis along z, centred at the origin, as fcl::Cylinder.
ContainingMesh containingCylinderMesh(double radius, double length, int sides = kCylinderSides);
// A subdivided icosahedron scaled until its every face lies at least `radius` from the centre.
ContainingMesh containingSphereMesh(double radius, int subdivisions = kSphereSubdivisions);

}  // namespace arcplan::collision::detail
