#include "mesh_part_cache.h"

#include <mutex>
#include <tuple>

#include "arcplan/robot/mesh.h"
#include "file_content.h"
#include "lru_cache.h"

namespace arcplan::collision::detail {
namespace {

// Everything meshParts' result depends on: the file's content (hash and size of its bytes), scale and
// the two BVH types. The convex switches only choose which of a part's geometries queries use, so
// models differing in them share parts.
using Key = std::tuple<std::size_t, std::size_t, double, double, double, BoundingVolume, BoundingVolume>;

Key keyOf(const std::filesystem::path& file, const Eigen::Vector3d& scale, const CollisionModelOptions& options) {
  const auto [hash, size] = fileContentKey(file);
  return {hash, size, scale.x(), scale.y(), scale.z(), options.collisionBoundingVolume, options.distanceBoundingVolume};
}

struct Cache {
  std::mutex mutex;
  LruCache<Key, std::vector<Part>> parts{kMeshPartCacheEntries};
};

Cache& cache() {
  static Cache instance;
  return instance;
}

}  // namespace

std::vector<Part> cachedMeshParts(const std::filesystem::path& file, const Eigen::Vector3d& scale,
                                  const CollisionModelOptions& options) {
  Cache& shared = cache();
  const Key key = keyOf(file, scale, options);
  {
    const std::lock_guard<std::mutex> lock(shared.mutex);
    if (const std::vector<Part>* found = shared.parts.find(key)) return *found;
  }
  // Built outside the lock: two threads may build the same entry once each; the first one is kept.
  std::vector<Part> parts = meshParts(robot::loadMesh(file, scale), options);
  // A file rewritten while it was loaded: these parts belong to neither content, so they are not kept.
  if (keyOf(file, scale, options) != key) return parts;
  const std::lock_guard<std::mutex> lock(shared.mutex);
  return shared.parts.insert(key, std::move(parts));
}

std::size_t meshPartCacheSize() {
  Cache& shared = cache();
  const std::lock_guard<std::mutex> lock(shared.mutex);
  return shared.parts.size();
}

}  // namespace arcplan::collision::detail
