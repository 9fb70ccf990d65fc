#include "containing_meshes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <fcl/narrowphase/distance.h>

#include "model_implementation.h"

namespace arcplan::collision::detail {

ContainingMesh containingCylinderMesh(double radius, double length, int sides) {
  // Every side face touches the cylinder along its middle line; the polygon's corners stick out most.
  const double pi = std::acos(-1.0);
  const double corner = radius / std::cos(pi / sides), half = length / 2.0;
  ContainingMesh result;
  auto& [vertices, triangles] = result.mesh;
  for (int i = 0; i < sides; ++i) {
    const double angle = 2.0 * pi * i / sides;
    const double x = corner * std::cos(angle), y = corner * std::sin(angle);
    vertices.emplace_back(x, y, -half);  // 2i: bottom
    vertices.emplace_back(x, y, half);   // 2i + 1: top
  }
  const int bottom = static_cast<int>(vertices.size()), top = bottom + 1;
  vertices.emplace_back(0.0, 0.0, -half);
  vertices.emplace_back(0.0, 0.0, half);
  for (int i = 0; i < sides; ++i) {
    const int j = (i + 1) % sides;
    triangles.emplace_back(2 * i, 2 * j, 2 * i + 1);
    triangles.emplace_back(2 * j, 2 * j + 1, 2 * i + 1);
    triangles.emplace_back(bottom, 2 * j, 2 * i);
    triangles.emplace_back(top, 2 * i + 1, 2 * j + 1);
  }
  result.largestGap = corner - radius;
  return result;
}

namespace {

// The icosahedron's 12 unit vertices and 20 outward faces.
robot::TriangleMesh icosahedron() {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  robot::TriangleMesh mesh;
  for (const auto& v :
       {Eigen::Vector3d(-1, t, 0), Eigen::Vector3d(1, t, 0), Eigen::Vector3d(-1, -t, 0), Eigen::Vector3d(1, -t, 0),
        Eigen::Vector3d(0, -1, t), Eigen::Vector3d(0, 1, t), Eigen::Vector3d(0, -1, -t), Eigen::Vector3d(0, 1, -t),
        Eigen::Vector3d(t, 0, -1), Eigen::Vector3d(t, 0, 1), Eigen::Vector3d(-t, 0, -1), Eigen::Vector3d(-t, 0, 1)})
    mesh.vertices.push_back(v.normalized());
  mesh.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                    {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  return mesh;
}

// Each face split in four, the new vertices pushed out onto the unit sphere.
robot::TriangleMesh subdivided(const robot::TriangleMesh& mesh) {
  robot::TriangleMesh result{mesh.vertices, {}};
  std::map<std::pair<int, int>, int> middles;
  const auto middle = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    const auto [it, added] = middles.emplace(key, static_cast<int>(result.vertices.size()));
    if (added) result.vertices.push_back((mesh.vertices[a] + mesh.vertices[b]).normalized());
    return it->second;
  };
  for (const auto& t : mesh.triangles) {
    const int ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
    result.triangles.insert(result.triangles.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
  }
  return result;
}

}  // namespace

ContainingMesh containingSphereMesh(double radius, int subdivisions) {
  ContainingMesh result;
  result.mesh = icosahedron();
  for (int s = 0; s < subdivisions; ++s) result.mesh = subdivided(result.mesh);
  // The unit vertices' faces come closest to the centre at their planes: scale those out to the radius.
  double nearestFace = 1.0;
  for (const auto& t : result.mesh.triangles) {
    const Eigen::Vector3d& a = result.mesh.vertices[t[0]];
    const Eigen::Vector3d normal = (result.mesh.vertices[t[1]] - a).cross(result.mesh.vertices[t[2]] - a).normalized();
    nearestFace = std::min(nearestFace, normal.dot(a));
  }
  const double scale = radius / nearestFace;
  for (auto& v : result.mesh.vertices) v *= scale;
  result.largestGap = scale - radius;
  return result;
}

double containingMeshGap(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
                         const CollisionModelOptions& options) {
  if (!options.hullLayer || (a.containingMesh == nullptr) == (b.containingMesh == nullptr)) return 0.0;
  const bool primitiveFirst = a.containingMesh != nullptr;
  const Part& primitive = primitiveFirst ? a : b;
  const Part& mesh = primitiveFirst ? b : a;
  if (mesh.triangleCount < kContainingMeshMinTriangles) return 0.0;
  const Eigen::Isometry3d& primitivePose = primitiveFirst ? poseA : poseB;
  const Eigen::Isometry3d& meshPose = primitiveFirst ? poseB : poseA;
  static const fcl::DistanceRequestd request(false, false, 0.0, 0.0, 1e-9);
  fcl::DistanceResultd result;
  const double d = fcl::distance(mesh.distanceGeometry.get(), meshPose, primitive.containingMesh.get(), primitivePose,
                                 request, result) -
                   kHullDistanceSlack;
  if (d <= 0.0) return 0.0;
  // The surfaces are apart, but the mesh part may lie inside the containing mesh (one of its points
  // does, then), or the primitive inside a closed mesh part (as partsDistance tests): no bound then.
  // Else the mesh part is outside the containing solid, and no nearer the primitive inside it.
  if (primitive.containingSolid.contains(primitivePose.inverse() * (meshPose * mesh.referencePoint)) ||
      mesh.solid.contains(meshPose.inverse() * (primitivePose * primitive.referencePoint)))
    return 0.0;
  return d;
}

}  // namespace arcplan::collision::detail
