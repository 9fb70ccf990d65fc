#pragma once
// Closed, outward-oriented triangle meshes of simple solids. They are what arcplan's own UR10e link
// meshes are made of (tools/generate_link_meshes.cpp), how the HTML report draws a URDF's box, sphere
// and cylinder shapes, and tests reuse them as solids with a known shape.
#include <Eigen/Core>

#include "arcplan/robot/mesh.h"

namespace arcplan::robot {

// A capped cylinder between the centres of its two end discs. The polygon is circumscribed
// (its vertices lie at radius / cos(pi / segments)), so the mesh contains the true cylinder and
// exceeds it by at most radius·(1 / cos(pi / segments) − 1) (0.5 % of the radius at 32 segments).
// Throws arcplan::Error for a non-positive radius, coincident end points or fewer than 3 segments.
TriangleMesh cylinderMesh(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius, int segments = 32);

// A box of edge lengths `size` along x, y, z, centred on the origin: 8 vertices, 12 triangles.
// Throws arcplan::Error for an edge length that is not positive.
TriangleMesh boxMesh(const Eigen::Vector3d& size);

// A sphere centred on the origin: `segments` vertices on each of segments / 2 − 1 rings of latitude
// (around z) and one at each pole. The vertices lie on the sphere, so the mesh is inside it.
// Throws arcplan::Error for a non-positive radius or fewer than 4 segments.
TriangleMesh sphereMesh(double radius, int segments = 16);

// Appends `part` as a separate component (vertices are not shared with what `mesh` holds already).
void appendMesh(TriangleMesh& mesh, const TriangleMesh& part);

// Volume enclosed by a closed mesh, positive when its triangles are counter-clockwise seen from
// outside (divergence theorem; overlapping components count twice).
double signedVolume(const TriangleMesh& mesh);

}  // namespace arcplan::robot
