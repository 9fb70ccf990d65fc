// Floors of the self pairs one joint alone moves against each other (ModelImplementation::PairGroup::floor), and
// the floor grids of those two joints move (PairGroup::floorGrid, pair_floor_grid.h).
//
// When only joint j changes the relative pose of two bodies, their distance is a function d(θ) of that
// joint's angle, and on any motion it changes by at most relativeReach_j per radian of θ (the motion
// bound of motion_bounds.cpp; it bounds every point of the bodies' hulls too, the farthest point of a
// hull from an axis being one of its vertices). Sampling θ at the centres of cells `step` wide and
// taking a lower bound b_k of d there gives d(θ) >= b_k − relativeReach_j·step/2 on cell k, so the
// smallest of those over one turn is a lower bound of d in every configuration. On MBM's UR5 the
// force sensor on wrist 3 turns against wrist 2 at 2.8 cm: without its floor every state check at 1 cm
// paid a GJK on the sensor's 4848-vertex hull for it (15 % of RRTConnect's collision time on
// bookshelf_thin 0006).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "lru_cache.h"
#include "model_implementation.h"
#include "pair_floor_grid.h"

namespace arcplan::collision::detail {
namespace {

// Floors stop at this (the planners' clearances are smaller; a larger one measures the pair as before).
constexpr double kFloorCap = 0.05;
// Cells are narrow enough that the distance changes by at most this within one [m], but no more than
// kMaxCells of them (a long tool on the last joint: fewer, wider cells, a lower floor, still a bound).
constexpr double kCellLoss = 5e-4;
constexpr int kMaxCells = 2048;
// A grid's cells lose at most this much of a part pair's distance. MBM's UR5: 110 x 50 cells for forearm_link –
// wrist_2_link, 87 x 111 for base_link – upper_arm_link (1–1.8 cm apart): most cells keep the 1.3 mm a self pair
// must keep on a certified motion.
constexpr double kGridCellLoss = 8e-3;

// The joints that move the group's bodies against each other.
std::vector<int> movingJoints(const Implementation::PairGroup& group) {
  std::vector<int> joints;
  for (int j = 0; j < group.relativeReach.size(); ++j)
    if (group.relativeReach[j] > 0.0) joints.push_back(j);
  return joints;
}

double groupFloor(const CollisionModel& model, const Implementation& impl, Workspace& data,
                  const Implementation::PairGroup& group, int joint) {
  // The relative pose repeats every turn, and queries take any finite angle, inside the joint's limits or not:
  // one whole turn, whatever the limits, so the floor holds for every state a query can be asked about.
  const double from = -M_PI, to = M_PI;
  const double reach = group.relativeReach[joint];
  const int cells = std::clamp(static_cast<int>(std::ceil((to - from) * reach / (2.0 * kCellLoss))), 1, kMaxCells);
  const double step = (to - from) / cells, loss = reach * step / 2.0;
  robot::JointVector q = robot::JointVector::Zero(model.robot().dof());
  double floor = std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector3d> axes(group.parts.size(), Eigen::Vector3d::Zero());  // kept from cell to cell
  for (int k = 0; k < cells && floor > 0.0; ++k) {
    q[joint] = from + (k + 0.5) * step;
    updateRobot(model, data, q);
    double nearest = kFloorCap;
    for (std::size_t p = 0; p < group.parts.size(); ++p) {
      const auto [i, j] = group.parts[p];
      ensurePart(impl, data, i);
      ensurePart(impl, data, j);
      // (A pair whose capsules are `nearest` apart returns that bound, which cannot lower `nearest`.)
      nearest = std::min(nearest, partPairLowerBound(impl.robotParts[i], data.partPoses[i], impl.robotParts[j],
                                                     data.partPoses[j], model.options(), nearest, axes[p]));
    }
    floor = std::min(floor, nearest - loss);
  }
  return std::max(floor, 0.0);
}

// Floors already measured, per process: a benchmark builds one model per problem and job for the same robot,
// and a floor costs ~20 ms (MBM's sensor pair: ~300 cells of hull GJKs). A group's floor depends only on its
// parts (their FCL geometries, offsets, capsules and links), the chain above their links, the joint and its
// reach, and the options that choose the bounds: all of it is written into the key. Parts built from the same
// mesh share their geometries (mesh_part_cache.h), so their addresses identify them; the entry holds those
// geometries, so no address is reused by another geometry while the entry exists.
struct FloorEntry {
  double floor = 0.0;
  std::shared_ptr<const PairFloorGrid> grid;  // two joints: its cells measured so far serve every model
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> geometries;
};

constexpr std::size_t kFloorCacheEntries = 64;

template <class T>
void append(std::string& key, const T& value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  key.append(bytes, sizeof(T));
}

void appendPart(std::string& key, std::vector<std::shared_ptr<fcl::CollisionGeometryd>>& geometries,
                const Implementation& impl, int i) {
  const Part& part = impl.robotParts[i];
  for (const auto* geometry : {&part.collisionGeometry, &part.distanceGeometry, &part.convexGeometry,
                               &part.hullGeometry, &part.coarseHullGeometry}) {
    append(key, geometry->get());
    if (*geometry) geometries.push_back(*geometry);
  }
  append(key, impl.robotPartLink[i]);
  append(key, part.offset.matrix().eval());
  append(key, part.capsule.start.eval());
  append(key, part.capsule.end.eval());
  append(key, part.capsule.radius);
}

std::string floorKey(const CollisionModel& model, const Implementation& impl, const Implementation::PairGroup& group,
                     const std::vector<int>& joints,
                     std::vector<std::shared_ptr<fcl::CollisionGeometryd>>& geometries) {
  std::string key;
  const CollisionModelOptions& options = model.options();
  append(key, options.convexDistance);
  append(key, options.hullLayer);
  for (const int joint : joints) {
    append(key, joint);
    append(key, group.relativeReach[joint]);
  }
  append(key, model.robot().dof());
  for (const auto& [i, j] : group.parts) {
    appendPart(key, geometries, impl, i);
    appendPart(key, geometries, impl, j);
  }
  for (const int body : {group.firstBody, group.secondBody}) {
    for (int l = impl.linkCapsuleLink[body]; l >= 0; l = model.robot().links()[l].parent) {
      const robot::Link& link = model.robot().links()[l];
      append(key, l);
      append(key, link.joint);
      append(key, link.originInParent.matrix().eval());
      append(key, link.axis.eval());
    }
  }
  return key;
}

struct FloorCache {
  std::mutex mutex;
  LruCache<std::string, FloorEntry> entries{kFloorCacheEntries};
};

FloorCache& floorCache() {
  static FloorCache instance;
  return instance;
}

std::shared_ptr<const PairFloorGrid> makeGrid(const CollisionModel& model, const Implementation& impl,
                                              const Implementation::PairGroup& group, int groupIndex,
                                              const std::vector<int>& joints) {
  std::vector<PairFloorGrid::PartPair> parts;
  for (std::size_t p = 0; p < group.parts.size(); ++p) {
    const auto [i, j] = group.parts[p];
    const Eigen::Index row = impl.firstPartPair[groupIndex] + static_cast<Eigen::Index>(p);
    parts.push_back({impl.robotParts[i], impl.robotParts[j], impl.robotPartLink[i], impl.robotPartLink[j],
                     impl.partPairReach(row, joints[0]), impl.partPairReach(row, joints[1])});
  }
  return std::make_shared<const PairFloorGrid>(model.sharedRobot(), model.options(), joints[0], joints[1],
                                               std::move(parts), kGridCellLoss);
}

}  // namespace

void measurePairFloors(const CollisionModel& model, Implementation& impl) {
  Workspace data(model);
  FloorCache& cache = floorCache();
  for (std::size_t s = 0; s < impl.selfGroups.size(); ++s) {
    auto& group = impl.selfGroups[s];
    if (group.rigid) continue;
    const std::vector<int> joints = movingJoints(group);
    if (joints.size() != 1 && joints.size() != 2) continue;
    FloorEntry entry;
    const std::string key = floorKey(model, impl, group, joints, entry.geometries);
    {
      const std::lock_guard<std::mutex> lock(cache.mutex);
      if (const FloorEntry* found = cache.entries.find(key)) {
        group.floor = found->floor;
        group.floorGrid = found->grid;
        continue;
      }
    }
    if (joints.size() == 1) {
      entry.floor = group.floor = groupFloor(model, impl, data, group, joints[0]);
    } else {  // measured cell by cell as queries ask
      entry.grid = group.floorGrid =
          makeGrid(model, impl, group, static_cast<int>(impl.obstacleGroups.size() + s), joints);
    }
    const std::lock_guard<std::mutex> lock(cache.mutex);
    cache.entries.insert(key, std::move(entry));
  }
}

}  // namespace arcplan::collision::detail
