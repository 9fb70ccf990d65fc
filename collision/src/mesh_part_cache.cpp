#include "mesh_part_cache.h"

#include <iterator>
#include <list>
#include <map>
#include <mutex>
#include <tuple>

#include "arcplan/robot/mesh.h"
#include "file_content.h"

namespace arcplan::collision::detail {
namespace {

// Everything meshParts' result depends on: the file's content (hash and size of its bytes), scale and
// options.
using Key = std::tuple<std::size_t, std::size_t, double, double, double, BoundingVolume, BoundingVolume, bool, bool>;

Key keyOf(const std::filesystem::path& file, const Eigen::Vector3d& scale, const CollisionModelOptions& options) {
  const auto [hash, size] = fileContentKey(file);
  return {hash,
          size,
          scale.x(),
          scale.y(),
          scale.z(),
          options.collisionBoundingVolume,
          options.distanceBoundingVolume,
          options.convexCollision,
          options.convexDistance};
}

// Least recently used first in `order`; `entries` points into it.
struct Cache {
  std::mutex mutex;
  std::list<std::pair<Key, std::vector<Part>>> order;
  std::map<Key, std::list<std::pair<Key, std::vector<Part>>>::iterator> entries;
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
    const auto found = shared.entries.find(key);
    if (found != shared.entries.end()) {
      shared.order.splice(shared.order.end(), shared.order, found->second);  // now the most recently used
      return found->second->second;
    }
  }
  // Built outside the lock: two threads may build the same entry once each; the first one is kept.
  std::vector<Part> parts = meshParts(robot::loadMesh(file, scale), options);
  // A file rewritten while it was loaded: these parts belong to neither content, so they are not kept.
  if (keyOf(file, scale, options) != key) return parts;
  const std::lock_guard<std::mutex> lock(shared.mutex);
  if (const auto found = shared.entries.find(key); found != shared.entries.end()) return found->second->second;
  shared.order.emplace_back(key, std::move(parts));
  shared.entries[key] = std::prev(shared.order.end());
  if (shared.order.size() > kMeshPartCacheEntries) {
    shared.entries.erase(shared.order.front().first);
    shared.order.pop_front();
  }
  return shared.order.back().second;
}

std::size_t meshPartCacheSize() {
  Cache& shared = cache();
  const std::lock_guard<std::mutex> lock(shared.mutex);
  return shared.order.size();
}

}  // namespace arcplan::collision::detail
