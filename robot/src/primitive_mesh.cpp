#include "arcplan/robot/primitive_mesh.h"

#include <cmath>

#include <Eigen/Geometry>

#include "arcplan/common/error.h"

namespace arcplan::robot {
namespace {

// A ring of `segments` vertices of radius r at height z, counter-clockwise seen from +z.
void addRing(TriangleMesh& mesh, double radius, double z, int segments) {
  for (int i = 0; i < segments; ++i) {
    const double angle = 2.0 * M_PI * i / segments;
    mesh.vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
  }
}

// Triangles between two rings of `segments` vertices starting at a and b (b above a).
void joinRings(TriangleMesh& mesh, int a, int b, int segments) {
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    mesh.triangles.emplace_back(a + i, a + j, b + j);
    mesh.triangles.emplace_back(a + i, b + j, b + i);
  }
}

// A fan from vertex `apex` to a ring; `up` says whether it faces +z.
void closeRing(TriangleMesh& mesh, int apex, int ring, int segments, bool up) {
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    if (up)
      mesh.triangles.emplace_back(apex, ring + i, ring + j);
    else
      mesh.triangles.emplace_back(apex, ring + j, ring + i);
  }
}

}  // namespace

TriangleMesh boxMesh(const Eigen::Vector3d& size) {
  if (!(size.minCoeff() > 0.0)) {
    throw Error("box mesh: edge lengths must be positive, got " + std::to_string(size.x()) + " " +
                std::to_string(size.y()) + " " + std::to_string(size.z()));
  }
  TriangleMesh mesh;
  const Eigen::Vector3d h = size / 2.0;
  for (int i = 0; i < 8; ++i)
    mesh.vertices.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z());
  // Two triangles per face, counter-clockwise seen from outside (corner bits: x = 1, y = 2, z = 4).
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.emplace_back(f[0], f[1], f[2]);
    mesh.triangles.emplace_back(f[0], f[2], f[3]);
  }
  return mesh;
}

TriangleMesh sphereMesh(double radius, int segments) {
  if (!(radius > 0.0)) throw Error("sphere mesh: radius must be positive, got " + std::to_string(radius));
  if (segments < 4) throw Error("sphere mesh: at least 4 segments needed, got " + std::to_string(segments));
  const int rings = segments / 2 - 1;  // latitude rings between the poles
  TriangleMesh mesh;
  for (int k = 1; k <= rings; ++k) {
    const double polar = M_PI * k / (rings + 1);
    addRing(mesh, radius * std::sin(polar), -radius * std::cos(polar), segments);
  }
  for (int k = 0; k + 1 < rings; ++k) joinRings(mesh, k * segments, (k + 1) * segments, segments);
  const int south = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, -radius);
  mesh.vertices.emplace_back(0.0, 0.0, radius);
  closeRing(mesh, south, 0, segments, false);
  closeRing(mesh, south + 1, (rings - 1) * segments, segments, true);
  return mesh;
}

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
