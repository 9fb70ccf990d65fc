// The per-process cache of link mesh parts (collision/src/mesh_part_cache.h): keyed by the file's content,
// so a mesh rewritten in place (same size, same modification time) is built again, and by what the
// parts depend on (scale, BVH types), and bounded, so a long session loading mesh after mesh keeps at
// most kMeshPartCacheEntries of them. The cache of robot descriptions the MoveIt readers share
// (collision/src/moveit_reading.h) is bounded the same way.
#include <algorithm>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>

#include "arcplan/robot/mesh.h"
#include "mesh_part_cache.h"
#include "moveit_reading.h"
#include "support/command.h"
#include "support/robot_files.h"

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

// meshParts reads only the BVH types of the options: a part carries its convex shape whether or not
// the convex switches send queries to it, so models differing only in those switches share the parts.
TEST(MeshPartCache, ModelsDifferingInTheConvexSwitchesShareOneEntryBvhTypesDoNot) {
  const auto dir = arcplan::testing::freshTempDirectory("mesh_part_cache_options");
  const auto file = dir / "link.stl";
  writeTetrahedron(file, 3);
  const CollisionModelOptions options;
  CollisionModelOptions noConvex = options;
  noConvex.convexCollision = noConvex.convexDistance = false;
  const auto built =
      arcplan::collision::detail::meshParts(arcplan::robot::loadMesh(file, Eigen::Vector3d::Ones()), noConvex);
  ASSERT_EQ(built.size(), 1u);
  EXPECT_NE(built.front().convexGeometry, nullptr);  // the closed tetrahedron's convex shape, switches off

  const auto first = cachedMeshParts(file, Eigen::Vector3d::Ones(), options);
  const std::size_t entries = arcplan::collision::detail::meshPartCacheSize();
  EXPECT_EQ(cachedMeshParts(file, Eigen::Vector3d::Ones(), noConvex).front().collisionGeometry.get(),
            first.front().collisionGeometry.get());
  EXPECT_EQ(arcplan::collision::detail::meshPartCacheSize(), entries);

  CollisionModelOptions aabb = options;
  aabb.collisionBoundingVolume = arcplan::collision::BoundingVolume::AABB;
  const auto other = cachedMeshParts(file, Eigen::Vector3d::Ones(), aabb);
  EXPECT_NE(other.front().collisionGeometry.get(), first.front().collisionGeometry.get());
  EXPECT_EQ(other.front().collisionGeometry->getNodeType(), fcl::BV_AABB);
  EXPECT_EQ(first.front().collisionGeometry->getNodeType(), fcl::BV_OBB);
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

// Descriptions with distinct contents (the UR10e's with a numbered comment) one after another: at most
// the bound is kept, the newest stays cached, the oldest is read again. A model and the frames of one
// description are one entry.
TEST(DescriptionCache, KeepsAtMostItsBoundDroppingTheLeastRecentlyUsed) {
  using arcplan::collision::MoveItRobot;
  using arcplan::collision::detail::descriptionCacheSize;
  using arcplan::collision::detail::kDescriptionCacheEntries;
  using arcplan::collision::detail::sharedUrdfFrames;
  const auto dir = arcplan::testing::freshTempDirectory("description_cache_bound");
  const std::string urdf = arcplan::testing::ur10eUrdfText();
  const auto robotNumber = [&](std::size_t k) {
    const auto file = dir / ("robot" + std::to_string(k) + ".urdf");
    if (!fs::exists(file)) std::ofstream(file) << urdf << "<!-- " << k << " -->\n";
    return MoveItRobot{file, {}};
  };
  const auto model = arcplan::collision::detail::sharedRobotModel(robotNumber(0));
  const std::size_t withModel = descriptionCacheSize();
  const auto oldest = sharedUrdfFrames(robotNumber(0));  // held, so a re-read cannot reuse its address
  EXPECT_EQ(descriptionCacheSize(), withModel);
  EXPECT_EQ(model->dof(), 6);
  const std::size_t count = kDescriptionCacheEntries + 6;
  std::shared_ptr<const arcplan::collision::detail::UrdfFrames> newest;
  for (std::size_t k = 1; k < count; ++k) {
    newest = sharedUrdfFrames(robotNumber(k));
    EXPECT_EQ(newest->root(), "base_link");
    EXPECT_LE(descriptionCacheSize(), kDescriptionCacheEntries);
  }
  EXPECT_EQ(descriptionCacheSize(), kDescriptionCacheEntries);
  EXPECT_EQ(sharedUrdfFrames(robotNumber(count - 1)).get(), newest.get());
  EXPECT_NE(sharedUrdfFrames(robotNumber(0)).get(), oldest.get());
}

}  // namespace
