// The per-process cache of link mesh parts (collision/src/mesh_part_cache.h): keyed by the file's content,
// so a mesh rewritten in place (same size, same modification time) is built again, and bounded, so a
// long session loading mesh after mesh keeps at most kMeshPartCacheEntries of them.
#include <algorithm>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>

#include "mesh_part_cache.h"
#include "support/command.h"

namespace {

namespace fs = std::filesystem;
using arcplan::collision::CollisionModelOptions;
using arcplan::collision::detail::cachedMeshParts;
using arcplan::collision::detail::Part;

// A closed tetrahedron with its apex at height `apex` (one digit, so every file has the same size).
void writeTetrahedron(const fs::path& file, int apex) {
  const std::string top = "0 0 " + std::to_string(apex);
  std::ofstream(file)
      << "solid t\n"
      << "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
      << "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex " << top << "\nendloop\nendfacet\n"
      << "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex " << top << "\nvertex 0 1 0\nendloop\nendfacet\n"
      << "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex " << top
      << "\nendloop\nendfacet\nendsolid t\n";
}

// The highest point of the parts, in the mesh's frame.
double topOf(const std::vector<Part>& parts) {
  double top = -std::numeric_limits<double>::infinity();
  for (const Part& part : parts) {
    for (const Eigen::Vector3d& point : part.hullPoints) top = std::max(top, (part.offset * point).z());
  }
  return top;
}

TEST(MeshPartCache, AFileRewrittenInPlaceWithinTheSameSecondIsBuiltAgain) {
  const auto dir = arcplan::testing::freshTempDirectory("mesh_part_cache_stale");
  const auto file = dir / "link.stl";
  const CollisionModelOptions options;
  writeTetrahedron(file, 1);
  const auto size = fs::file_size(file);
  const auto written = fs::last_write_time(file);
  const auto first = cachedMeshParts(file, Eigen::Vector3d::Ones(), options);
  EXPECT_DOUBLE_EQ(topOf(first), 1.0);
  // Asked again: the same parts (shared FCL geometry), not a rebuild.
  const auto again = cachedMeshParts(file, Eigen::Vector3d::Ones(), options);
  ASSERT_EQ(again.size(), first.size());
  EXPECT_EQ(again.front().collisionGeometry.get(), first.front().collisionGeometry.get());

  writeTetrahedron(file, 2);
  fs::last_write_time(file, written);  // same size and time: only the content tells them apart
  ASSERT_EQ(fs::file_size(file), size);
  ASSERT_EQ(fs::last_write_time(file), written);
  EXPECT_DOUBLE_EQ(topOf(cachedMeshParts(file, Eigen::Vector3d::Ones(), options)), 2.0);
  // A scale is part of the key too.
  EXPECT_DOUBLE_EQ(topOf(cachedMeshParts(file, Eigen::Vector3d(1, 1, 3), options)), 6.0);
}

TEST(MeshPartCache, KeepsAtMostItsBoundDroppingTheLeastRecentlyUsed) {
  const auto dir = arcplan::testing::freshTempDirectory("mesh_part_cache_bound");
  const CollisionModelOptions options;
  const std::size_t count = arcplan::collision::detail::kMeshPartCacheEntries + 6;
  std::vector<fs::path> files;
  std::vector<const void*> geometry;
  std::vector<Part> oldest;  // held, so a rebuilt entry cannot reuse its address
  // Distinct contents: apex heights 1..9 and scales 1..8 (scale changes the key, not the file).
  for (std::size_t k = 0; k < count; ++k) {
    files.push_back(dir / ("m" + std::to_string(k % 9) + ".stl"));
    if (k < 9) writeTetrahedron(files.back(), static_cast<int>(k + 1));
    const Eigen::Vector3d scale(1.0, 1.0, 1.0 + static_cast<double>(k / 9));
    const auto parts = cachedMeshParts(files.back(), scale, options);
    EXPECT_DOUBLE_EQ(topOf(parts), static_cast<double>(k % 9 + 1) * scale.z());
    geometry.push_back(parts.front().collisionGeometry.get());
    if (k == 0) oldest = parts;
    EXPECT_LE(arcplan::collision::detail::meshPartCacheSize(), arcplan::collision::detail::kMeshPartCacheEntries);
  }
  EXPECT_EQ(arcplan::collision::detail::meshPartCacheSize(), arcplan::collision::detail::kMeshPartCacheEntries);
  // The newest is still cached (same geometry); the oldest was dropped and is built anew.
  const auto scaleOf = [](std::size_t k) { return Eigen::Vector3d(1.0, 1.0, 1.0 + static_cast<double>(k / 9)); };
  EXPECT_EQ(cachedMeshParts(files.back(), scaleOf(count - 1), options).front().collisionGeometry.get(),
            geometry.back());
  EXPECT_NE(cachedMeshParts(files.front(), scaleOf(0), options).front().collisionGeometry.get(), geometry.front());
}

}  // namespace
