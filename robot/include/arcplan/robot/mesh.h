#pragma once
// Triangle meshes for collision: loaded with assimp (STL, OBJ, DAE, PLY and the rest of assimp's
// formats), merged into one vertex/triangle list in the file's frame, scaled.
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace arcplan::robot {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  // counter-clockwise seen from outside
};

// Throws arcplan::Error naming the file when assimp cannot read it or it has no triangles.
TriangleMesh loadMesh(const std::filesystem::path& file, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

}  // namespace arcplan::robot
