#include "drawn_meshes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "base64.h"

namespace arcplan::report::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A ring of `segments` vertices of radius r at height z, counter-clockwise seen from +z.
void addRing(robot::TriangleMesh& mesh, double radius, double z, int segments) {
  for (int i = 0; i < segments; ++i) {
    const double angle = 2.0 * kPi * i / segments;
    mesh.vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
  }
}

// Triangles between two rings of `segments` vertices starting at a and b (b above a).
void joinRings(robot::TriangleMesh& mesh, int a, int b, int segments) {
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    mesh.triangles.emplace_back(a + i, a + j, b + j);
    mesh.triangles.emplace_back(a + i, b + j, b + i);
  }
}

// A fan from vertex `apex` to a ring; `up` says whether it faces +z.
void closeRing(robot::TriangleMesh& mesh, int apex, int ring, int segments, bool up) {
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    if (up)
      mesh.triangles.emplace_back(apex, ring + i, ring + j);
    else
      mesh.triangles.emplace_back(apex, ring + j, ring + i);
  }
}

robot::TriangleMesh clustered(const robot::TriangleMesh& mesh, double cell, const Eigen::Vector3d& low) {
  std::map<std::array<long, 3>, int> cellIndex;
  std::vector<Eigen::Vector3d> sums;
  std::vector<int> counts, vertexCell(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d grid = ((mesh.vertices[i] - low) / cell).array().floor();
    const std::array<long, 3> key{long(grid.x()), long(grid.y()), long(grid.z())};
    const auto [found, added] = cellIndex.emplace(key, static_cast<int>(sums.size()));
    if (added) {
      sums.push_back(Eigen::Vector3d::Zero());
      counts.push_back(0);
    }
    vertexCell[i] = found->second;
    sums[static_cast<std::size_t>(found->second)] += mesh.vertices[i];
    ++counts[static_cast<std::size_t>(found->second)];
  }
  robot::TriangleMesh result;
  for (std::size_t c = 0; c < sums.size(); ++c) result.vertices.push_back(sums[c] / counts[c]);
  std::set<std::array<int, 3>> seen;  // two triangles on the same three cells draw the same facet
  for (const auto& triangle : mesh.triangles) {
    const Eigen::Vector3i t(vertexCell[static_cast<std::size_t>(triangle.x())],
                            vertexCell[static_cast<std::size_t>(triangle.y())],
                            vertexCell[static_cast<std::size_t>(triangle.z())]);
    if (t.x() == t.y() || t.y() == t.z() || t.x() == t.z()) continue;
    std::array<int, 3> key{t.x(), t.y(), t.z()};
    std::sort(key.begin(), key.end());
    if (seen.insert(key).second) result.triangles.push_back(t);
  }
  return result;
}

}  // namespace

robot::TriangleMesh boxMesh(const Eigen::Vector3d& size) {
  robot::TriangleMesh mesh;
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

robot::TriangleMesh cylinderMesh(double radius, double length, int segments) {
  segments = std::max(segments, 3);
  robot::TriangleMesh mesh;
  addRing(mesh, radius, -length / 2.0, segments);
  addRing(mesh, radius, length / 2.0, segments);
  joinRings(mesh, 0, segments, segments);
  mesh.vertices.emplace_back(0.0, 0.0, -length / 2.0);
  mesh.vertices.emplace_back(0.0, 0.0, length / 2.0);
  closeRing(mesh, 2 * segments, 0, segments, false);
  closeRing(mesh, 2 * segments + 1, segments, segments, true);
  return mesh;
}

robot::TriangleMesh sphereMesh(double radius, int segments) {
  segments = std::max(segments, 4);
  const int rings = segments / 2 - 1;  // latitude rings between the poles
  robot::TriangleMesh mesh;
  for (int k = 1; k <= rings; ++k) {
    const double polar = kPi * k / (rings + 1);
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

robot::TriangleMesh withAtMostTriangles(const robot::TriangleMesh& mesh, std::size_t maxTriangles) {
  if (mesh.triangles.size() <= maxTriangles || mesh.vertices.empty()) return mesh;
  Eigen::Vector3d low = mesh.vertices.front(), high = low;
  for (const auto& v : mesh.vertices) {
    low = low.cwiseMin(v);
    high = high.cwiseMax(v);
  }
  const double diagonal = (high - low).norm();
  for (double cell = diagonal / 400.0;; cell *= 1.25) {
    auto result = clustered(mesh, cell, low);
    if (result.triangles.size() <= maxTriangles || cell > diagonal) return result;
  }
}

nlohmann::json meshJson(const robot::TriangleMesh& mesh) {
  std::vector<float> positions;
  positions.reserve(3 * mesh.vertices.size());
  for (const auto& v : mesh.vertices) {
    positions.insert(positions.end(),
                     {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    for (int corner = 0; corner < 3; ++corner) indices.push_back(static_cast<std::uint32_t>(t[corner]));
  }
  return {{"vertices", mesh.vertices.size()},
          {"triangles", mesh.triangles.size()},
          {"positions", base64Of(positions)},
          {"indices", base64Of(indices)}};
}

}  // namespace arcplan::report::detail
