// Generates arcplan's UR10e collision meshes (data/ur10e/meshes/<link>.stl) from the link-radius
// table of ur10e-facts.md §4.3: every link is a set of capped cylinders in its ROS link frame
// (the URDF's collision origins are the identity). Each cylinder stays a separate closed,
// outward-oriented component; FCL and the point-in-mesh tests work on such compound meshes,
// and a union would gain nothing but code. The table covers every vertex of UR's visual meshes
// within 5 mm, so each link mesh covers the real link well inside the 1 cm the project asks for.
//
// Usage: arcplan_generate_link_meshes [OUTPUT_DIR]   (default: <data dir>/ur10e/meshes)
#include <iostream>
#include <string>
#include <vector>

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/primitive_mesh.h"

namespace {

using arcplan::robot::TriangleMesh;
using Eigen::Vector3d;

struct LinkCylinder {
  Vector3d start, end;  // centres of the end discs, link frame [m]
  double radius;        // [m]
};

struct LinkShape {
  std::string link;
  std::vector<LinkCylinder> cylinders;
};

// ur10e-facts.md §4.3, one row per cylinder: (axis, centre of the other two coordinates, radius,
// axial range) written as end points.
const std::vector<LinkShape>& ur10eLinkShapes() {
  static const std::vector<LinkShape> shapes{
      {"base_link_inertia", {{{0, 0, 0}, {0, 0, 0.0993}, 0.095}}},
      {"shoulder_link",
       {{{0, 0, -0.0817}, {0, 0, 0.0939}, 0.0765},    // shoulder-pan housing
        {{0, -0.0946, 0}, {0, 0.0765, 0}, 0.0765}}},  // shoulder-lift housing
      {"upper_arm_link",
       {{{0, 0, 0.0948}, {0, 0, 0.2694}, 0.0767},                // shoulder-lift housing
        {{-0.6127, 0, 0.1762}, {0, 0, 0.1762}, 0.0553},          // tube
        {{-0.105, 0, 0.1762}, {0, 0, 0.1762}, 0.075},            // collar at the shoulder
        {{-0.6127, 0, 0.1762}, {-0.535, 0, 0.1762}, 0.0601},     // collar at the elbow
        {{-0.6127, 0, 0.0986}, {-0.6127, 0, 0.2482}, 0.0601}}},  // elbow housing
      {"forearm_link",
       {{{0, 0, -0.0189}, {0, 0, 0.0987}, 0.0588},                 // elbow housing
        {{-0.57155, 0, 0.0393}, {0, 0, 0.0393}, 0.0427},           // tube
        {{-0.09, 0, 0.0393}, {0, 0, 0.0393}, 0.0585},              // collar at the elbow
        {{-0.57155, 0, 0.0393}, {-0.505, 0, 0.0393}, 0.0455},      // collar at the wrist
        {{-0.57155, 0, -0.0181}, {-0.57155, 0, 0.1060}, 0.047}}},  // wrist-1 housing
      {"wrist_1_link", {{{0, 0, -0.0683}, {0, 0, 0.0472}, 0.047}, {{0, -0.0666, 0}, {0, 0.0575, 0}, 0.047}}},
      {"wrist_2_link", {{{0, 0, -0.0534}, {0, 0, 0.0465}, 0.047}, {{0, -0.0570, 0}, {0, 0.0679, 0}, 0.047}}},
      {"wrist_3_link",
       {{{0, 0, -0.0489}, {0, 0, 0}, 0.0452},
        {{0, 0, -0.045}, {0, 0, -0.030}, 0.0516}}},  // the local bump next to the wrist-3 motor
  };
  return shapes;
}

// Binary STL through assimp's exporter, so the files are written by the same library that reads them.
std::string binaryStl(const TriangleMesh& mesh) {
  aiScene scene;  // owns and frees everything attached below
  scene.mRootNode = new aiNode();
  scene.mMaterials = new aiMaterial* [1] { new aiMaterial() };
  scene.mNumMaterials = 1;
  auto* aiMeshPtr = new aiMesh();
  scene.mMeshes = new aiMesh* [1] { aiMeshPtr };
  scene.mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned[1]{0};
  scene.mRootNode->mNumMeshes = 1;

  aiMeshPtr->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  aiMeshPtr->mNumVertices = static_cast<unsigned>(mesh.vertices.size());
  aiMeshPtr->mVertices = new aiVector3D[mesh.vertices.size()];
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const auto& p = mesh.vertices[i];
    aiMeshPtr->mVertices[i] =
        aiVector3D(static_cast<ai_real>(p.x()), static_cast<ai_real>(p.y()), static_cast<ai_real>(p.z()));
  }
  aiMeshPtr->mNumFaces = static_cast<unsigned>(mesh.triangles.size());
  aiMeshPtr->mFaces = new aiFace[mesh.triangles.size()];
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    aiFace& face = aiMeshPtr->mFaces[f];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) face.mIndices[k] = static_cast<unsigned>(mesh.triangles[f][k]);
  }

  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(&scene, "stlb");
  if (blob == nullptr) throw arcplan::Error(std::string("assimp cannot export STL: ") + exporter.GetErrorString());
  return std::string(static_cast<const char*>(blob->data), blob->size);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc > 2) throw arcplan::Error("usage: arcplan_generate_link_meshes [OUTPUT_DIR]");
    const std::filesystem::path outputDirectory =
        argc == 2 ? std::filesystem::path(argv[1]) : arcplan::dataDirectory() / "ur10e" / "meshes";
    std::filesystem::create_directories(outputDirectory);
    constexpr int kSegments = 32;
    for (const auto& shape : ur10eLinkShapes()) {
      TriangleMesh mesh;
      for (const auto& c : shape.cylinders) {
        arcplan::robot::appendMesh(mesh, arcplan::robot::cylinderMesh(c.start, c.end, c.radius, kSegments));
      }
      const auto file = outputDirectory / (shape.link + ".stl");
      arcplan::writeFileAtomically(file, binaryStl(mesh));
      std::cout << file.string() << ": " << shape.cylinders.size() << " cylinders, " << mesh.triangles.size()
                << " triangles, volume " << arcplan::robot::signedVolume(mesh) << " m^3 (overlaps counted)\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "arcplan_generate_link_meshes: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
