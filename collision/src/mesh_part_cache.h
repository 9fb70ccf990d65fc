#pragma once
// The parts of a robot's link meshes, built once per process: loading a mesh and building its parts
// (components, FCL BVHs, convex shapes) is by far the most expensive step of a CollisionModel (the
// MotionBenchMaker UR5 + Robotiq 85 meshes: ~1.2 s per model, docs/benchmarks.md), and a benchmark
// builds one model per problem and job for the same robot. Parts are immutable once built (their FCL
// geometries are only read by queries), so models share them.
#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "parts.h"

namespace arcplan::collision::detail {

// meshParts(robot::loadMesh(file, scale), options), from the cache when the same file (same size and
// modification time), scale and narrow-phase options were built before. Thread-safe. Throws as
// robot::loadMesh does (nothing is cached then).
std::vector<Part> cachedMeshParts(const std::filesystem::path& file, const Eigen::Vector3d& scale,
                                  const CollisionModelOptions& options);

}  // namespace arcplan::collision::detail
