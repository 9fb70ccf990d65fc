#include "arcplan/robot/primitive_mesh.h"

#include <cmath>

#include <Eigen/Geometry>

#include "arcplan/common/error.h"

namespace arcplan::robot {

TriangleMesh cylinderMesh(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius, int segments) {
  const Eigen::Vector3d axis = end - start;
  if (!(radius > 0.0)) throw Error("cylinder mesh: radius must be positive, got " + std::to_string(radius));
  if (!(axis.norm() > 0.0)) throw Error("cylinder mesh: start and end points coincide");
  if (segments < 3) throw Error("cylinder mesh: at least 3 segments needed, got " + std::to_string(segments));

  // Any two unit vectors orthogonal to the axis span the cross-section; u × v = axis direction
  // makes the counter-clockwise order below face outward.
  const Eigen::Vector3d direction = axis.normalized();
  const Eigen::Vector3d u = direction.unitOrthogonal();
  const Eigen::Vector3d v = direction.cross(u);
  const double vertexRadius = radius / std::cos(M_PI / segments);

  TriangleMesh mesh;
  mesh.vertices.reserve(2 * segments + 2);
  for (int i = 0; i < segments; ++i) {
    const double angle = 2.0 * M_PI * i / segments;
    const Eigen::Vector3d offset = vertexRadius * (std::cos(angle) * u + std::sin(angle) * v);
    mesh.vertices.push_back(start + offset);  // index 2i: bottom ring
    mesh.vertices.push_back(end + offset);    // index 2i + 1: top ring
  }
  const int bottomCenter = 2 * segments, topCenter = 2 * segments + 1;
  mesh.vertices.push_back(start);
  mesh.vertices.push_back(end);

  mesh.triangles.reserve(4 * segments);
  for (int i = 0; i < segments; ++i) {
    const int bottom = 2 * i, top = 2 * i + 1;
    const int nextBottom = 2 * ((i + 1) % segments), nextTop = nextBottom + 1;
    mesh.triangles.emplace_back(bottom, nextBottom, nextTop);
    mesh.triangles.emplace_back(bottom, nextTop, top);
    mesh.triangles.emplace_back(bottomCenter, nextBottom, bottom);  // bottom cap faces -axis
    mesh.triangles.emplace_back(topCenter, top, nextTop);           // top cap faces +axis
  }
  return mesh;
}

void appendMesh(TriangleMesh& mesh, const TriangleMesh& part) {
  const int offset = static_cast<int>(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
  for (const auto& triangle : part.triangles) mesh.triangles.push_back(triangle + Eigen::Vector3i::Constant(offset));
}

double signedVolume(const TriangleMesh& mesh) {
  double sixTimesVolume = 0.0;
  for (const auto& t : mesh.triangles) {
    sixTimesVolume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return sixTimesVolume / 6.0;
}

}  // namespace arcplan::robot
