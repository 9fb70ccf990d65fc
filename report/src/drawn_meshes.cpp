#include "drawn_meshes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "base64.h"

namespace arcplan::report::detail {
namespace {

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
