#include "arcplan/collision/collision_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "model_implementation.h"
#include "sphere_prefilter.h"

namespace arcplan::collision {
namespace {

using detail::Implementation;
using detail::Part;
using detail::Workspace;

// FCL compares surfaces; a part entirely inside the other has no intersecting surfaces, so one
// point of each is tested against the other's solid as well.
bool oneInsideOther(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB) {
  return a.solid.contains(poseA.inverse() * (poseB * b.referencePoint)) ||
         b.solid.contains(poseB.inverse() * (poseA * a.referencePoint));
}

}  // namespace

namespace detail {

const ModelImplementation& implementationOf(const CollisionModel& model) { return *model.implementation_; }
Workspace& workspaceOf(CollisionData& data) { return *data.workspace_; }

Workspace::Workspace(const CollisionModel& model)
    : kinematics(model.robot()),
      partPoses(implementationOf(model).robotParts.size()),
      capsuleStarts(implementationOf(model).robotParts.size()),
      capsuleEnds(implementationOf(model).robotParts.size()),
      partStamps(implementationOf(model).robotParts.size(), 0),
      linkCapsuleStarts(model.linkNames().size()),
      linkCapsuleEnds(model.linkNames().size()),
      motionPairs(implementationOf(model).groups.size()),
      motionJoints(model.robot().dof()) {
  distanceOrder.reserve(implementationOf(model).partPairs.size());
  if (const auto& prefilter = implementationOf(model).prefilter) {
    spheres = std::make_shared<SphereWorkspace>();
    prefilter->prepare(*spheres);
  }
}

void updateRobot(const CollisionModel& model, Workspace& data, const robot::JointRef& q) {
  if (q.size() != model.robot().dof()) {
    throw Error("collision query: expected " + std::to_string(model.robot().dof()) + " joint values, got " +
                std::to_string(q.size()));
  }
  const Implementation& impl = detail::implementationOf(model);
  robot::forwardKinematics(model.robot(), q, data.kinematics);
  ++data.stamp;
  for (std::size_t b = 0; b < impl.linkCapsules.size(); ++b) {
    const Eigen::Isometry3d& linkPose = data.kinematics.linkPoses[impl.linkCapsuleLink[b]];
    data.linkCapsuleStarts[b] = linkPose * impl.linkCapsules[b].start;
    data.linkCapsuleEnds[b] = linkPose * impl.linkCapsules[b].end;
  }
}

double linkGap(const Implementation& impl, const Workspace& data, const Implementation::PairGroup& group) {
  const int a = group.firstBody;
  const double radius = impl.linkCapsules[a].radius;
  if (group.self) {
    const int b = group.secondBody;
    return segmentDistance(data.linkCapsuleStarts[a], data.linkCapsuleEnds[a], data.linkCapsuleStarts[b],
                           data.linkCapsuleEnds[b]) -
           radius - impl.linkCapsules[b].radius;
  }
  double gap = std::numeric_limits<double>::infinity();
  for (const int j : group.obstacleParts) {
    gap = std::min(gap, obstacleGap(impl, data.linkCapsuleStarts[a], data.linkCapsuleEnds[a], radius, j));
  }
  return gap;
}

double partsDistance(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
                     bool boundsOverlap, const CollisionModelOptions& options) {
  // No relative or absolute error allowance. libccd's GJK stops once an iteration improves the
  // distance by less than distance_tolerance; FCL's default 1e-6 left errors up to 4e-5 m against the
  // exact triangle distances of the BVHs, 1e-9 agrees with them to 1e-6 m.
  static const fcl::DistanceRequestd request(false, false, 0.0, 0.0, 1e-9);
  fcl::DistanceResultd result;
  double d = 0.0;
  if (options.convexDistance && a.convexGeometry && b.convexGeometry) {
    d = fcl::distance(a.convexGeometry.get(), poseA, b.convexGeometry.get(), poseB, request, result);
  } else {
    if (boundsOverlap && oneInsideOther(a, poseA, b, poseB)) return 0.0;
    d = fcl::distance(a.distanceGeometry.get(), poseA, b.distanceGeometry.get(), poseB, request, result);
  }
  return std::max(d, 0.0);  // FCL reports -1 or 0 for intersecting shapes
}

}  // namespace detail

namespace {

using detail::boundGap;
using detail::ensurePart;
using detail::partsDistance;
using detail::secondPart;
using detail::secondPose;
using detail::updateRobot;

// Whether the capsule around a whole link already clears the group's other body.
bool linksApart(const Implementation& impl, const Workspace& data, const Implementation::PairGroup& group) {
  return detail::linkGap(impl, data, group) > 0.0;
}

bool partsCollide(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
                  const CollisionModelOptions& options) {
  static const fcl::CollisionRequestd request;  // one contact, no contact details: boolean answer
  fcl::CollisionResultd result;
  if (options.convexCollision && a.convexGeometry && b.convexGeometry) {
    return fcl::collide(a.convexGeometry.get(), poseA, b.convexGeometry.get(), poseB, request, result) > 0;
  }
  if (fcl::collide(a.collisionGeometry.get(), poseA, b.collisionGeometry.get(), poseB, request, result) > 0)
    return true;
  return oneInsideOther(a, poseA, b, poseB);
}

bool groupCollides(const CollisionModel& model, Workspace& data, const Implementation::PairGroup& group) {
  const Implementation& impl = detail::implementationOf(model);
  const bool broadPhase = model.options().broadPhase;
  if (broadPhase && linksApart(impl, data, group)) return false;
  for (const auto& [i, j] : group.parts) {
    if (broadPhase && boundGap(impl, data, i, j, group.self) > 0.0) continue;
    ensurePart(impl, data, i);
    if (group.self) ensurePart(impl, data, j);
    if (partsCollide(impl.robotParts[i], data.partPoses[i], secondPart(impl, group, j),
                     secondPose(impl, data, group, j), model.options())) {
      return true;
    }
  }
  return false;
}

NamePair namesOf(const CollisionModel& model, const Implementation::PairGroup& group) {
  return {model.linkNames()[group.firstBody],
          group.self ? model.linkNames()[group.secondBody] : model.obstacleNames()[group.secondBody]};
}

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
        return detail::meshParts(robot::loadMesh(geometry.meshFile, geometry.meshScale), options);
      } catch (const Error& e) {
        throw Error("link " + linkName + ": " + e.what());
      }
    case robot::CollisionGeometry::Shape::Box:
      return {detail::boxPart(geometry.boxSize)};
    case robot::CollisionGeometry::Shape::Sphere:
      return {detail::spherePart(geometry.radius)};
    case robot::CollisionGeometry::Shape::Cylinder:
      return {detail::cylinderPart(geometry.radius, geometry.length)};
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
      return {detail::spherePart(obstacle.radius)};
    case Obstacle::Shape::Box: {
      Part box = detail::boxPart(obstacle.size);
      box.boxBound = true;
      return {std::move(box)};
    }
    case Obstacle::Shape::Cylinder:
      return {detail::cylinderPart(obstacle.radius, obstacle.length)};
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
      for (const auto& [i, j] : group.parts) impl.partPairs.push_back({&group, i, j});
    }
  }
}

}  // namespace

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

CollisionData::CollisionData(const CollisionModel& model) : workspace_(std::make_unique<detail::Workspace>(model)) {}
CollisionData::~CollisionData() = default;

std::string describeCollisions(const CollisionReport& report) {
  std::vector<std::string> pairs;
  for (const auto& [first, second] : report.collisions) pairs.push_back(first + "–" + second);
  return joinText(pairs, ", ");
}

namespace detail {

bool exactlyCollisionFree(const CollisionModel& model, Workspace& data, const robot::JointRef& q) {
  updateRobot(model, data, q);
  const Implementation& impl = detail::implementationOf(model);
  for (const auto* groups : {&impl.obstacleGroups, &impl.selfGroups}) {
    for (const auto& group : *groups) {
      if (groupCollides(model, data, group)) return false;
    }
  }
  return true;
}

}  // namespace detail

bool isCollisionFree(const CollisionModel& model, CollisionData& workspace, const robot::JointRef& q) {
  Workspace& data = detail::workspaceOf(workspace);
  const Implementation& impl = detail::implementationOf(model);
  if (impl.prefilter && detail::sphereFree(*impl.prefilter, *data.spheres, q)) return true;
  return detail::exactlyCollisionFree(model, data, q);
}

CollisionReport collide(const CollisionModel& model, CollisionData& workspace, const robot::JointRef& q) {
  Workspace& data = detail::workspaceOf(workspace);
  const Implementation& impl = detail::implementationOf(model);
  CollisionReport report;
  if (impl.prefilter && detail::sphereFree(*impl.prefilter, *data.spheres, q)) return report;
  updateRobot(model, data, q);
  for (const auto* groups : {&impl.obstacleGroups, &impl.selfGroups}) {
    for (const auto& group : *groups) {
      if (groupCollides(model, data, group)) report.collisions.push_back(namesOf(model, group));
    }
  }
  report.valid = report.collisions.empty();
  return report;
}

DistanceReport distance(const CollisionModel& model, CollisionData& workspace, const robot::JointRef& q) {
  Workspace& data = detail::workspaceOf(workspace);
  updateRobot(model, data, q);
  const Implementation& impl = detail::implementationOf(model);
  for (std::size_t i = 0; i < impl.robotParts.size(); ++i) ensurePart(impl, data, static_cast<int>(i));
  // Part pairs nearest first by the lower bound their bounding volumes give; a pair whose bound
  // is not below the best distance found so far cannot improve it.
  data.distanceOrder.clear();
  for (std::size_t k = 0; k < impl.partPairs.size(); ++k) {
    const auto& pair = impl.partPairs[k];
    const double bound =
        model.options().broadPhase ? boundGap(impl, data, pair.first, pair.second, pair.group->self) : 0.0;
    data.distanceOrder.emplace_back(bound, static_cast<int>(k));
  }
  std::sort(data.distanceOrder.begin(), data.distanceOrder.end());

  DistanceReport report;
  for (const auto& [bound, index] : data.distanceOrder) {
    const auto& candidate = impl.partPairs[index];
    const bool self = candidate.group->self;
    double& best = self ? report.selfDistance : report.obstacleDistance;
    if (bound >= std::max(report.selfDistance, report.obstacleDistance)) break;
    if (bound >= best) continue;
    const double d =
        partsDistance(impl.robotParts[candidate.first], data.partPoses[candidate.first],
                      secondPart(impl, *candidate.group, candidate.second),
                      secondPose(impl, data, *candidate.group, candidate.second), bound <= 0.0, model.options());
    if (d < best) {
      best = d;
      (self ? report.selfPair : report.obstaclePair) = namesOf(model, *candidate.group);
    }
  }
  return report;
}

}  // namespace arcplan::collision
