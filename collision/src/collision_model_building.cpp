// CollisionModel's construction: bodies and parts of the robot, its attached objects and the
// scene's obstacles, and the pairs to check (queries on a built model are in collision_model.cpp).
#include "arcplan/collision/collision_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "mesh_part_cache.h"
#include "model_implementation.h"
#include "sphere_prefilter.h"

namespace arcplan::collision {
namespace {

using detail::Implementation;
using detail::Part;
using detail::Workspace;

}  // namespace
const char* toString(BoundingVolume boundingVolume) {
  switch (boundingVolume) {
    case BoundingVolume::AABB:
      return "AABB";
    case BoundingVolume::OBB:
      return "OBB";
    case BoundingVolume::RSS:
      return "RSS";
    case BoundingVolume::kIOS:
      return "kIOS";
    case BoundingVolume::OBBRSS:
      return "OBBRSS";
  }
  return "?";
}

namespace {

// The parts of one collision geometry of a link, in the geometry's own frame.
std::vector<Part> geometryParts(const robot::CollisionGeometry& geometry, const std::string& linkName,
                                const CollisionModelOptions& options) {
  switch (geometry.shape) {
    case robot::CollisionGeometry::Shape::Mesh:
      try {
        return detail::cachedMeshParts(geometry.meshFile, geometry.meshScale, options);  // once per process
      } catch (const Error& e) {
        throw Error("link " + linkName + ": " + e.what());
      }
    case robot::CollisionGeometry::Shape::Box:
      return {detail::boxPart(geometry.boxSize)};
    case robot::CollisionGeometry::Shape::Sphere:
      return {detail::spherePart(geometry.radius, options.distanceBoundingVolume)};
    case robot::CollisionGeometry::Shape::Cylinder:
      return {detail::cylinderPart(geometry.radius, geometry.length, options.distanceBoundingVolume)};
  }
  return {};
}

// One body per link with collision geometry (its name appended to linkNames), its parts and the
// capsule around the whole link.
void addRobotParts(const robot::RobotModel& robot, const CollisionModelOptions& options, Implementation& impl,
                   std::vector<std::string>& linkNames) {
  const auto& links = robot.links();
  for (std::size_t l = 0; l < links.size(); ++l) {
    if (links[l].collisions.empty()) continue;
    const int body = static_cast<int>(linkNames.size());
    linkNames.push_back(links[l].name);
    std::vector<detail::Capsule> partCapsules;
    for (const auto& geometry : links[l].collisions) {
      for (auto& part : geometryParts(geometry, links[l].name, options)) {
        part.body = body;
        part.offset = geometry.origin;
        partCapsules.push_back({part.offset * part.capsule.start, part.offset * part.capsule.end, part.capsule.radius});
        impl.robotParts.push_back(std::move(part));
        impl.robotPartLink.push_back(static_cast<int>(l));
      }
    }
    impl.linkCapsules.push_back(detail::enclosingCapsule(partCapsules));
    impl.linkCapsuleLink.push_back(static_cast<int>(l));
  }
}

// The parts of an obstacle, in the obstacle's own frame.
std::vector<Part> obstacleShapeParts(const Obstacle& obstacle, const CollisionModelOptions& options) {
  switch (obstacle.shape) {
    case Obstacle::Shape::Sphere:
      return {detail::spherePart(obstacle.radius, options.distanceBoundingVolume)};
    case Obstacle::Shape::Box: {
      Part box = detail::boxPart(obstacle.size);
      box.boxBound = true;
      return {std::move(box)};
    }
    case Obstacle::Shape::Cylinder:
      return {detail::cylinderPart(obstacle.radius, obstacle.length, options.distanceBoundingVolume)};
    case Obstacle::Shape::Mesh:
      try {
        return detail::meshParts(
            obstacle.meshData ? *obstacle.meshData : robot::loadMesh(obstacle.meshFile, obstacle.meshScale), options);
      } catch (const Error& e) {
        throw Error("obstacle " + obstacle.name + ": " + e.what());
      }
  }
  return {};
}

// Bodies the robot holds: one body each (its name appended to linkNames), moving with its link.
void addAttachedParts(const Scene& scene, const robot::RobotModel& robot, const CollisionModelOptions& options,
                      Implementation& impl, std::vector<std::string>& linkNames) {
  for (const auto& attached : scene.attachedObstacles) {
    const int link = robot.linkIndex(attached.link);
    const int body = static_cast<int>(linkNames.size());
    linkNames.push_back(attached.body.name);
    std::vector<detail::Capsule> partCapsules;
    for (auto& part : obstacleShapeParts(attached.body, options)) {
      part.body = body;
      part.offset = attached.body.pose;
      partCapsules.push_back({part.offset * part.capsule.start, part.offset * part.capsule.end, part.capsule.radius});
      impl.robotParts.push_back(std::move(part));
      impl.robotPartLink.push_back(link);
    }
    impl.linkCapsules.push_back(detail::enclosingCapsule(partCapsules));
    impl.linkCapsuleLink.push_back(link);
  }
}

// One body per obstacle (its name appended to obstacleNames), its parts placed in the world with the
// capsules and inverse poses the distance bounds use.
void addObstacleParts(const Scene& scene, const CollisionModelOptions& options, Implementation& impl,
                      std::vector<std::string>& obstacleNames) {
  for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
    const Obstacle& obstacle = scene.obstacles[o];
    obstacleNames.push_back(obstacle.name);
    for (auto& part : obstacleShapeParts(obstacle, options)) {
      part.body = static_cast<int>(o);
      part.offset = obstacle.pose;
      impl.obstacleCapsuleStarts.push_back(obstacle.pose * part.capsule.start);
      impl.obstacleCapsuleEnds.push_back(obstacle.pose * part.capsule.end);
      impl.obstacleInversePoses.push_back(obstacle.pose.inverse());
      impl.obstacleParts.push_back(std::move(part));
    }
  }
}

// A misspelled name in the allowed pairs would silently allow nothing: every name must be a link
// (with or without geometry) or an obstacle.
void checkAllowedNames(const AllowedCollisionMatrix& allowed, const robot::RobotModel& robot,
                       const std::vector<std::string>& obstacleNames, const std::vector<std::string>& bodyNames) {
  std::set<std::string> known(obstacleNames.begin(), obstacleNames.end());
  known.insert(bodyNames.begin(), bodyNames.end());  // links with geometry and attached bodies
  for (const auto& link : robot.links()) known.insert(link.name);
  for (const auto& [first, second] : allowed.pairs()) {
    for (const auto& name : {first, second}) {
      if (!known.count(name)) {
        throw Error("allowed collisions: unknown link or obstacle '" + name + "' (pair " + first + ", " + second +
                    "); known: " + joinText({known.begin(), known.end()}, ", "));
      }
    }
  }
}

// The pairs of bodies that are checked (not allowed to touch), each with its pairs of parts.
void addPairGroups(const AllowedCollisionMatrix& allowed, const std::vector<std::string>& linkNames,
                   const std::vector<std::string>& obstacleNames, Implementation& impl) {
  for (int a = 0; a < static_cast<int>(linkNames.size()); ++a) {
    for (int b = 0; b < static_cast<int>(obstacleNames.size()); ++b) {
      if (allowed.isAllowed(linkNames[a], obstacleNames[b])) continue;
      Implementation::PairGroup group{a, b, false, {}, {}, {}};
      for (std::size_t j = 0; j < impl.obstacleParts.size(); ++j) {
        if (impl.obstacleParts[j].body == b) group.obstacleParts.push_back(static_cast<int>(j));
      }
      for (std::size_t i = 0; i < impl.robotParts.size(); ++i) {
        if (impl.robotParts[i].body != a) continue;
        for (const int j : group.obstacleParts) group.parts.emplace_back(i, j);
      }
      impl.obstacleGroups.push_back(std::move(group));
    }
    for (int b = a + 1; b < static_cast<int>(linkNames.size()); ++b) {
      if (allowed.isAllowed(linkNames[a], linkNames[b])) continue;
      Implementation::PairGroup group{a, b, true, {}, {}, {}};
      for (std::size_t i = 0; i < impl.robotParts.size(); ++i) {
        for (std::size_t j = 0; j < impl.robotParts.size(); ++j) {
          if (impl.robotParts[i].body == a && impl.robotParts[j].body == b) group.parts.emplace_back(i, j);
        }
      }
      impl.selfGroups.push_back(std::move(group));
    }
  }
  // Pointers into obstacleGroups and selfGroups: taken only once both are complete.
  for (const auto* groups : {&impl.obstacleGroups, &impl.selfGroups}) {
    for (const auto& group : *groups) {
      impl.groups.push_back(&group);
      impl.firstPartPair.push_back(static_cast<int>(impl.partPairs.size()));
      for (const auto& [i, j] : group.parts) impl.partPairs.push_back({&group, i, j});
    }
  }
}

}  // namespace

void detail::measureRigidPairs(const CollisionModel& model, Implementation& impl) {
  Workspace data(model);
  updateRobot(model, data, robot::JointVector::Zero(model.robot().dof()));
  std::vector<std::pair<double, std::pair<int, int>>> order;
  for (auto& group : impl.selfGroups) {
    if (group.relativeReach.size() > 0 && group.relativeReach.maxCoeff() > 0.0) continue;
    group.rigidCollides = groupCollides(model, data, group);
    group.rigidDistance = std::numeric_limits<double>::infinity();
    // The smallest part-pair distance, nearest bounds first as distance() measures it: a part pair whose
    // capsule or hull bound is not below the smallest distance so far cannot lower it (MBM's force sensor
    // against the gripper: 8 groups of up to 19 × 4 part pairs, ~100 ms per model when all were measured).
    order.clear();
    for (const auto& [i, j] : group.parts) order.push_back({boundGap(impl, data, i, j, true), {i, j}});  // places both
    std::sort(order.begin(), order.end());
    for (const auto& [bound, parts] : order) {
      double& best = group.rigidDistance;
      if (bound >= best) break;
      const auto [i, j] = parts;
      const Part &a = impl.robotParts[i], &b = impl.robotParts[j];
      if (hullGap(a, data.partPoses[i], b, data.partPoses[j], model.options(), best) >= best) continue;
      best = std::min(best, partsDistance(a, data.partPoses[i], b, data.partPoses[j], bound <= 0.0, model.options()));
    }
    group.rigid = true;
  }
}

CollisionModel::CollisionModel(std::shared_ptr<const robot::RobotModel> robot, const Scene& scene,
                               AllowedCollisionMatrix allowed, CollisionModelOptions options)
    : robot_(std::move(robot)),
      allowed_(std::move(allowed)),
      options_(options),
      implementation_(std::make_unique<detail::ModelImplementation>()) {
  if (!robot_) throw Error("collision model: no robot model");
  if (options_.distanceBoundingVolume == BoundingVolume::OBB) {
    throw Error("collision model: FCL 0.7 computes no mesh–mesh distance with OBB; use RSS, kIOS or OBBRSS");
  }
  Implementation& impl = *implementation_;
  addRobotParts(*robot_, options_, impl, linkNames_);
  addAttachedParts(scene, *robot_, options_, impl, linkNames_);
  addObstacleParts(scene, options_, impl, obstacleNames_);
  checkAllowedNames(allowed_, *robot_, obstacleNames_, linkNames_);
  addPairGroups(allowed_, linkNames_, obstacleNames_, impl);
  detail::computeMotionBounds(*robot_, impl);
  detail::measureRigidPairs(*this, impl);
  detail::measurePairFloors(*this, impl);
  if (options_.spherePrefilter)
    impl.prefilter = std::make_shared<const detail::SpherePrefilter>(*robot_, impl, linkNames_);
}

CollisionModel::~CollisionModel() = default;

std::size_t CollisionModel::robotObstaclePairCount() const { return implementation_->obstacleGroups.size(); }
std::size_t CollisionModel::selfPairCount() const { return implementation_->selfGroups.size(); }

std::shared_ptr<const CollisionModel> makeCollisionModel(const Scene& scene, CollisionModelOptions options) {
  auto robot = scene.robot.isBuiltIn() ? std::make_shared<const robot::RobotModel>(robot::ur10e())
                                       : std::make_shared<const robot::RobotModel>(robot::loadRobot(scene.robot));
  AllowedCollisionMatrix allowed = robotAllowedCollisions(*robot, scene.robot.srdf);
  for (const auto& [first, second] : scene.allowedCollisions) allowed.allow(first, second);
  return std::make_shared<const CollisionModel>(std::move(robot), scene, std::move(allowed), options);
}

}  // namespace arcplan::collision
