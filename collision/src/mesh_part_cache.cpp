#include "mesh_part_cache.h"

#include <map>
#include <mutex>
#include <tuple>

#include "arcplan/robot/mesh.h"

namespace arcplan::collision::detail {
namespace {

// Everything meshParts' result depends on. The file's size and modification time make an edited
// mesh a new entry (a long-lived process, e.g. the Python module, may see the file change).
using Key = std::tuple<std::string, std::uintmax_t, std::filesystem::file_time_type::rep, double, double, double,
                       BoundingVolume, BoundingVolume, bool, bool>;

Key keyOf(const std::filesystem::path& file, const Eigen::Vector3d& scale, const CollisionModelOptions& options) {
  std::error_code sizeError, timeError;
  const std::uintmax_t size = std::filesystem::file_size(file, sizeError);
  const auto modified = std::filesystem::last_write_time(file, timeError);
  return {std::filesystem::absolute(file).lexically_normal().string(),
          sizeError ? 0 : size,
          timeError ? 0 : modified.time_since_epoch().count(),
          scale.x(),
          scale.y(),
          scale.z(),
          options.collisionBoundingVolume,
          options.distanceBoundingVolume,
          options.convexCollision,
          options.convexDistance};
}

}  // namespace

std::vector<Part> cachedMeshParts(const std::filesystem::path& file, const Eigen::Vector3d& scale,
                                  const CollisionModelOptions& options) {
  static std::mutex mutex;
  static std::map<Key, std::vector<Part>> cache;
  const Key key = keyOf(file, scale, options);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto found = cache.find(key);
    if (found != cache.end()) return found->second;
  }
  // Built outside the lock: two threads may build the same entry once each; the first one is kept.
  std::vector<Part> parts = meshParts(robot::loadMesh(file, scale), options);
  const std::lock_guard<std::mutex> lock(mutex);
  return cache.emplace(key, std::move(parts)).first->second;
}

}  // namespace arcplan::collision::detail
