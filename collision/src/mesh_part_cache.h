#pragma once
// The parts of a robot's link meshes, built once per process: loading a mesh and building its parts
// (components, FCL BVHs, convex shapes) is by far the most expensive step of a CollisionModel (the
// MotionBenchMaker UR5 + Robotiq 85 meshes: ~1.2 s per model, docs/benchmarks.md), and a benchmark
// builds one model per problem and job for the same robot. Parts are immutable once built (their FCL
// geometries are only read by queries), so models share them.
#include <cstddef>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "parts.h"

namespace arcplan::collision::detail {

// At most this many meshes (file content × scale × BVH types) are kept, the least recently used dropped
// first: a robot has a few dozen mesh files, and a long Python session that loads one description
// after another must not keep every mesh it ever saw. Models already built keep their parts.
inline constexpr std::size_t kMeshPartCacheEntries = 64;

// meshParts(robot::loadMesh(file, scale), options), from the cache when a file with the same content
// (a hash of its bytes and its size: a file rewritten in place, even within the same second, is a new
// entry), scale and BVH types (options.collisionBoundingVolume, distanceBoundingVolume: the only options
// meshParts reads) was built before. Thread-safe. Throws as robot::loadMesh
// does (nothing is cached then).
std::vector<Part> cachedMeshParts(const std::filesystem::path& file, const Eigen::Vector3d& scale,
                                  const CollisionModelOptions& options);

// How many meshes the cache holds now (for tests of its bound).
std::size_t meshPartCacheSize();

}  // namespace arcplan::collision::detail
