#include "arcplan/robot/mesh.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "arcplan/common/error.h"

namespace arcplan::robot {
namespace {

void appendNode(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parentTransform,
                const Eigen::Vector3d& scale, TriangleMesh& out) {
  const aiMatrix4x4 transform = parentTransform * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const int firstVertex = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out.vertices.emplace_back(p.x * scale.x(), p.y * scale.y(), p.z * scale.z());
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no volume
      out.triangles.emplace_back(firstVertex + static_cast<int>(face.mIndices[0]),
                                 firstVertex + static_cast<int>(face.mIndices[1]),
                                 firstVertex + static_cast<int>(face.mIndices[2]));
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) appendNode(scene, *node.mChildren[c], transform, scale, out);
}

}  // namespace

TriangleMesh loadMesh(const std::filesystem::path& file, const Eigen::Vector3d& scale) {
  if (!std::filesystem::exists(file)) throw Error("mesh file " + file.string() + " does not exist");
  Assimp::Importer importer;
  // Collada files carry a unit and up-axis that assimp applies through the node transforms, which
  // appendNode folds in; vertices are joined so FCL's BVH gets a connected mesh.
  const aiScene* scene =
      importer.ReadFile(file.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw Error("cannot read mesh " + file.string() + ": " + importer.GetErrorString());
  }
  TriangleMesh mesh;
  appendNode(*scene, *scene->mRootNode, aiMatrix4x4(), scale, mesh);
  if (mesh.triangles.empty()) throw Error("mesh " + file.string() + " has no triangles");
  return mesh;
}

}  // namespace arcplan::robot
