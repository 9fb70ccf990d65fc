#pragma once
// Triangle meshes as the 3D view draws them: large meshes thinned to a triangle budget (a
// 43 000-triangle force sensor would make the page megabytes larger and look the same at report
// scale), and the page's encoding (base64 Float32 positions, Uint32 triangle corners). A URDF's
// primitive shapes are tessellated by robot/primitive_mesh.h.
#include <cstddef>

#include <nlohmann/json.hpp>

#include "arcplan/robot/mesh.h"

namespace arcplan::report::detail {

// Vertex clustering (Rossignac and Borrel): vertices on one cell of a grid become their mean, and
// triangles whose corners merge disappear. The cell grows from 1/400 of the bounding box's diagonal
// until at most maxTriangles are left; a mesh already within the budget is returned unchanged.
robot::TriangleMesh withAtMostTriangles(const robot::TriangleMesh& mesh, std::size_t maxTriangles);

// {vertices, triangles, positions, indices}: counts, and base64 of little-endian Float32 x, y, z
// per vertex and Uint32 corners per triangle.
nlohmann::json meshJson(const robot::TriangleMesh& mesh);

}  // namespace arcplan::report::detail
