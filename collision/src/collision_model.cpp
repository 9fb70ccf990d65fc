#include "arcplan/collision/collision_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "model_implementation.h"
#include "pair_floor_grid.h"
#include "sphere_prefilter.h"

namespace arcplan::collision {
namespace {

using detail::Implementation;
using detail::kHullDistanceSlack;
using detail::Part;
using detail::Workspace;

// The coarse hull where there is one, else the hull.
const fcl::CollisionGeometryd* coarseHullOf(const Part& part) {
  return part.coarseHullGeometry ? part.coarseHullGeometry.get() : part.hullGeometry.get();
}

// The direction between GJK's nearest points (world frame) in the first part's frame; left as it was where the
// hulls touch (no direction).
void keepAxis(const fcl::DistanceResultd& result, const Eigen::Isometry3d& poseA, Eigen::Vector3d& axis) {
  const Eigen::Vector3d between = result.nearest_points[1] - result.nearest_points[0];
  const double length = between.norm();
  if (result.min_distance > 0.0 && length > 0.0) axis = poseA.linear().transpose() * (between / length);
}

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
      pairAxes(implementationOf(model).partPairs.size(), Eigen::Vector3d::Zero()),
      pairAxisMotions(implementationOf(model).partPairs.size(), 0),
      motionJoints(model.robot().dof()),
      probeJoints(model.robot().dof()) {
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
                     bool boundsOverlap, const CollisionModelOptions& options, Eigen::Vector3d* axis) {
  // No relative or absolute error allowance. libccd's GJK stops once an iteration improves the
  // distance by less than distance_tolerance; FCL's default 1e-6 left errors up to 4e-5 m against the
  // exact triangle distances of the BVHs, 1e-9 agrees with them to 1e-6 m.
  static const fcl::DistanceRequestd request(false, false, 0.0, 0.0, 1e-9);
  static const fcl::DistanceRequestd withPoints(true, false, 0.0, 0.0, 1e-9);
  fcl::DistanceResultd result;
  double d = 0.0;
  if (options.convexDistance && a.convexGeometry && b.convexGeometry) {
    d = fcl::distance(a.convexGeometry.get(), poseA, b.convexGeometry.get(), poseB, axis ? withPoints : request,
                      result);
    if (axis != nullptr) keepAxis(result, poseA, *axis);
  } else {
    if (boundsOverlap && oneInsideOther(a, poseA, b, poseB)) return 0.0;
    d = fcl::distance(a.distanceGeometry.get(), poseA, b.distanceGeometry.get(), poseB, request, result);
  }
  return std::max(d, 0.0);  // FCL reports -1 or 0 for intersecting shapes
}

double hullGap(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
               const CollisionModelOptions& options, double enough) {
  Eigen::Vector3d none = Eigen::Vector3d::Zero();
  return hullGap(a, poseA, b, poseB, options, enough, none);
}

double supportAlong(const Part& part, const Eigen::Vector3d& direction) {
  if (!part.hullGeometry) return std::numeric_limits<double>::infinity();
  if (part.hullGeometry->getNodeType() == fcl::GEOM_CONVEX) {
    double highest = -std::numeric_limits<double>::infinity();
    for (const auto& v : static_cast<const fcl::Convexd&>(*part.hullGeometry).getVertices())
      highest = std::max(highest, direction.dot(v));
    return highest;
  }
  // The primitives in their FCL frames (centred; a cylinder along z), whose support functions are closed-form.
  const detail::Solid& solid = part.solid;
  switch (solid.kind) {
    case detail::Solid::Kind::Box:
      return solid.halfExtents.dot(direction.cwiseAbs());
    case detail::Solid::Kind::Sphere:
      return solid.radius * direction.norm();
    case detail::Solid::Kind::Cylinder:
      return solid.radius * std::hypot(direction.x(), direction.y()) + solid.halfLength * std::abs(direction.z());
    default:
      return std::numeric_limits<double>::infinity();
  }
}

double separatingGap(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
                     const Eigen::Vector3d& axisInA) {
  // a reaches at most supportA(n) beyond its origin along n, b at least −supportB(−n) (both in their own frames).
  const Eigen::Vector3d world = poseA.linear() * axisInA;
  const double highestA = supportAlong(a, axisInA) + world.dot(poseA.translation());
  const double lowestB = -supportAlong(b, -(poseB.linear().transpose() * world)) + world.dot(poseB.translation());
  return lowestB - highestA;  // −infinity where a part has no support function
}

double hullGap(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
               const CollisionModelOptions& options, double enough, Eigen::Vector3d& axis) {
  if (!options.hullLayer || !a.hullGeometry || !b.hullGeometry) return 0.0;
  if (!axis.isZero()) {
    // Rounding of the dot products (~1e-16 m per vertex coordinate) is far below the slack taken off.
    const double along = separatingGap(a, poseA, b, poseB, axis) - kHullDistanceSlack;
    if (along >= enough) return along;
  }
  // Convex parts are their own hulls: partsDistance's GJK on them (which keeps its direction) is the measurement.
  if (options.convexDistance && a.convexGeometry && b.convexGeometry) return 0.0;
  static const fcl::DistanceRequestd request(true, false, 0.0, 0.0, 1e-9);
  fcl::DistanceResultd result;
  if (a.coarseHullGeometry || b.coarseHullGeometry) {
    const double coarse = fcl::distance(coarseHullOf(a), poseA, coarseHullOf(b), poseB, request, result);
    if (coarse - kHullDistanceSlack >= enough) {
      keepAxis(result, poseA, axis);
      return std::max(coarse - kHullDistanceSlack, 0.0);
    }
    result.clear();
  }
  const double d = fcl::distance(a.hullGeometry.get(), poseA, b.hullGeometry.get(), poseB, request, result);
  keepAxis(result, poseA, axis);
  return std::max(d - kHullDistanceSlack, 0.0);
}

bool witnessCloser(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
                   double distance) {
  if (!(distance > 0.0)) return false;
  const Eigen::Isometry3d toB = poseB.inverse(Eigen::Isometry) * poseA;
  const double squared = distance * distance;
  if (b.boxBound) {
    for (const auto& point : a.witnessPoints) {
      const Eigen::Vector3d outside = ((toB * point).cwiseAbs() - b.boxHalfExtents).cwiseMax(0.0);
      if (outside.squaredNorm() < squared) return true;
    }
    return false;
  }
  // Against a curved primitive the nearest vertex of a gripper closing on it is rarely extreme along a fixed
  // direction: every vertex (hullPoints) is asked. A point's distance is closed-form here, nanoseconds per vertex,
  // where FCL's exact distance of a 1776-triangle finger tip from a can costs 2–3 ms (a GJK per triangle).
  const Solid& solid = b.solid;
  if (solid.kind == Solid::Kind::Cylinder) {  // axis z, centred, as fcl::Cylinder
    for (const auto& vertex : a.hullPoints) {
      const Eigen::Vector3d point = toB * vertex;
      const double radial = std::max(std::hypot(point.x(), point.y()) - solid.radius, 0.0);
      const double axial = std::max(std::abs(point.z()) - solid.halfLength, 0.0);
      if (radial * radial + axial * axial < squared) return true;
    }
  } else if (solid.kind == Solid::Kind::Sphere) {
    const double reach = solid.radius + distance;
    for (const auto& vertex : a.hullPoints)
      if ((toB * vertex).squaredNorm() < reach * reach) return true;
  }
  return false;
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
  // The hulls contain the parts: hulls apart, parts apart (one GJK instead of a BVH traversal); the
  // coarse hulls contain the hulls.
  if (options.hullLayer && a.hullGeometry && b.hullGeometry) {
    if ((a.coarseHullGeometry || b.coarseHullGeometry) &&
        fcl::collide(coarseHullOf(a), poseA, coarseHullOf(b), poseB, request, result) == 0) {
      return false;
    }
    result.clear();
    if (fcl::collide(a.hullGeometry.get(), poseA, b.hullGeometry.get(), poseB, request, result) == 0) return false;
  }
  result.clear();
  if (fcl::collide(a.collisionGeometry.get(), poseA, b.collisionGeometry.get(), poseB, request, result) > 0)
    return true;
  return oneInsideOther(a, poseA, b, poseB);
}

}  // namespace

bool detail::groupCollides(const CollisionModel& model, Workspace& data, const Implementation::PairGroup& group) {
  if (group.rigid) return group.rigidCollides;
  if (group.floor > 0.0) return false;
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

// Appends to data.openPairs the part pairs of group k (impl.groups) that its capsules (the link's,
// the parts') do not prove at least `required` apart; false if the group is known closer (rigid).
bool addOpenPairs(const CollisionModel& model, Workspace& data, int k, double required) {
  const Implementation& impl = detail::implementationOf(model);
  const Implementation::PairGroup& group = *impl.groups[k];
  if (group.rigid) return group.rigidDistance >= required;
  if (group.floor >= required || detail::linkGap(impl, data, group) >= required) return true;
  for (std::size_t p = 0; p < group.parts.size(); ++p) {
    const auto [i, j] = group.parts[p];
    const double bound = boundGap(impl, data, i, j, group.self);  // also places both parts
    if (bound >= required) continue;
    data.openPairs.emplace_back(impl.firstPartPair[k] + static_cast<int>(p), bound <= 0.0);
  }
  return true;
}

NamePair detail::namesOf(const CollisionModel& model, const Implementation::PairGroup& group) {
  return {model.linkNames()[group.firstBody],
          group.self ? model.linkNames()[group.secondBody] : model.obstacleNames()[group.secondBody]};
}

namespace {

using detail::groupCollides;
using detail::namesOf;

}  // namespace

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

bool unclearedPairsCollide(const CollisionModel& model, Workspace& data, const robot::JointRef& q, int lane,
                           const char* skip) {
  const Implementation& impl = detail::implementationOf(model);
  const SpherePrefilter& prefilter = *impl.prefilter;
  const int bodies = prefilter.tables().bodyCount;
  bool placed = false;
  const auto place = [&] {
    if (!placed) updateRobot(model, data, q);
    placed = true;
  };
  // The pairs whose spheres touch, deepest first: in a state that collides, the pair whose spheres overlap most is the
  // likeliest to, and its answer ends the check (the answer is any pair's, whatever the order).
  auto& uncleared = data.spheres->uncleared;
  uncleared.clear();
  for (int p = 0; p < prefilter.pairCount(); ++p) {
    const float gap = data.spheres->gaps[p * prefilter::kLanes + lane];
    if ((skip != nullptr && skip[p]) || gap > 0.0f) continue;
    // A gap that is not a number (no finite sphere) proves nothing: FCL is asked, first, and the sort stays ordered.
    uncleared.emplace_back(std::isnan(gap) ? -std::numeric_limits<float>::infinity() : gap, p);
  }
  std::sort(uncleared.begin(), uncleared.end());
  for (const auto& [gap, p] : uncleared) {
    if (p >= bodies) {
      const auto& group = impl.selfGroups[prefilter.selfGroupOf(p - bodies)];
      if (group.floorGrid && group.floorGrid->at(q, groupAxes(impl, data, group)) > 0.0) continue;
      place();
      if (groupCollides(model, data, group)) return true;
      continue;
    }
    for (const auto& group : impl.obstacleGroups) {
      if (group.firstBody != p) continue;
      place();
      if (groupCollides(model, data, group)) return true;
    }
  }
  return false;
}

}  // namespace detail

bool isCollisionFree(const CollisionModel& model, CollisionData& workspace, const robot::JointRef& q) {
  Workspace& data = detail::workspaceOf(workspace);
  const Implementation& impl = detail::implementationOf(model);
  // (A state of the wrong size: exactlyCollisionFree throws the usual message.)
  if (!impl.prefilter || !impl.prefilter->usable() || q.size() != impl.prefilter->dof())
    return detail::exactlyCollisionFree(model, data, q);
  if (detail::sphereFree(*impl.prefilter, *data.spheres, q)) return true;
  // FCL for the pairs whose spheres touch: on MBM's UR5 two self pairs' spheres overlap in every state, and a full
  // check passed all ~400 pair groups through their capsules for them.
  for (int lane = 0; lane < detail::prefilter::kLanes; ++lane) impl.prefilter->loadLane(*data.spheres, lane, q.data());
  detail::collisionGaps(*impl.prefilter, *data.spheres);
  return !detail::unclearedPairsCollide(model, data, q, 0);
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

namespace {

// Every part pair with the lower bound its bounding volumes (and floor) give at q, nearest first, in
// data.distanceOrder: the order distance queries measure them in.
void orderPartPairs(const CollisionModel& model, Workspace& data, const robot::JointRef& q) {
  updateRobot(model, data, q);
  const Implementation& impl = detail::implementationOf(model);
  for (std::size_t i = 0; i < impl.robotParts.size(); ++i) ensurePart(impl, data, static_cast<int>(i));
  data.distanceOrder.clear();
  for (std::size_t k = 0; k < impl.partPairs.size(); ++k) {
    const auto& pair = impl.partPairs[k];
    const double bound =
        std::max(model.options().broadPhase ? boundGap(impl, data, pair.first, pair.second, pair.group->self) : 0.0,
                 pair.group->floor);
    data.distanceOrder.emplace_back(bound, static_cast<int>(k));
  }
  std::sort(data.distanceOrder.begin(), data.distanceOrder.end());
}

// The exact distance of part pair `index` (its bound from orderPartPairs), or +inf where its hulls or containing meshes
// show it is at least `below` apart.
double distanceIfBelow(const CollisionModel& model, Workspace& data, int index, double bound, double below) {
  const Implementation& impl = detail::implementationOf(model);
  const auto& candidate = impl.partPairs[index];
  const Part& first = impl.robotParts[candidate.first];
  const Part& second = secondPart(impl, *candidate.group, candidate.second);
  const Eigen::Isometry3d& secondPose = detail::secondPose(impl, data, *candidate.group, candidate.second);
  if (detail::hullGap(first, data.partPoses[candidate.first], second, secondPose, model.options(), below) >= below ||
      detail::containingMeshGap(first, data.partPoses[candidate.first], second, secondPose, model.options()) >= below)
    return std::numeric_limits<double>::infinity();
  return partsDistance(first, data.partPoses[candidate.first], second, secondPose, bound <= 0.0, model.options());
}

}  // namespace

DistanceReport distance(const CollisionModel& model, CollisionData& workspace, const robot::JointRef& q) {
  Workspace& data = detail::workspaceOf(workspace);
  const Implementation& impl = detail::implementationOf(model);
  // Part pairs nearest first by the lower bound their bounding volumes give; a pair whose bound
  // is not below the best distance found so far cannot improve it.
  orderPartPairs(model, data, q);
  DistanceReport report;
  for (const auto& group : impl.selfGroups) {
    if (group.rigid && group.rigidDistance < report.selfDistance) {
      report.selfDistance = group.rigidDistance;
      report.selfPair = namesOf(model, group);
    }
  }
  for (const auto& [bound, index] : data.distanceOrder) {
    const auto& candidate = impl.partPairs[index];
    if (candidate.group->rigid) continue;
    const bool self = candidate.group->self;
    double& best = self ? report.selfDistance : report.obstacleDistance;
    if (bound >= std::max(report.selfDistance, report.obstacleDistance)) break;
    if (bound >= best) continue;
    const double d = distanceIfBelow(model, data, index, bound, best);
    if (d < best) {
      best = d;
      (self ? report.selfPair : report.obstaclePair) = namesOf(model, *candidate.group);
    }
  }
  return report;
}

detail::LeastPair detail::leastOffsetPair(const CollisionModel& model, CollisionData& workspace,
                                          const robot::JointRef& q, double obstacleOffset, double selfOffset) {
  Workspace& data = detail::workspaceOf(workspace);
  const Implementation& impl = detail::implementationOf(model);
  orderPartPairs(model, data, q);
  LeastPair least;
  // Better: less of distance − offset, an obstacle pair before a self pair as far.
  const auto take = [&](const Implementation::PairGroup& group, double d) {
    const double value = d - (group.self ? selfOffset : obstacleOffset);
    if (value < least.value || (value == least.value && least.group != nullptr && least.group->self && !group.self)) {
      least = {&group, d, value};
    }
  };
  for (const auto& group : impl.selfGroups)
    if (group.rigid) take(group, group.rigidDistance);
  const double largestOffset = std::max(obstacleOffset, selfOffset);
  for (const auto& [bound, index] : data.distanceOrder) {
    if (bound - largestOffset > least.value) break;  // nor can any pair after it, nearest first
    const auto& candidate = impl.partPairs[index];
    if (candidate.group->rigid) continue;
    const double offset = candidate.group->self ? selfOffset : obstacleOffset;
    if (bound - offset > least.value) continue;
    // At most as far as the best (ties decided by take), measured where its bounds allow it.
    const double below = std::nextafter(least.value + offset, std::numeric_limits<double>::infinity());
    const double d = distanceIfBelow(model, data, index, bound, below);
    if (std::isfinite(d)) take(*candidate.group, d);
  }
  return least;
}

bool hasClearance(const CollisionModel& model, CollisionData& workspace, const robot::JointRef& q, double clearance) {
  if (!(clearance > 0.0) || !std::isfinite(clearance)) {
    throw Error("clearance query: clearance must be a finite distance > 0 m, got " + std::to_string(clearance));
  }
  // Every pair keeps what the clearance asks of its kind (requiredDistance): self pairs at most kSelfClearance.
  return detail::keepsDistances(model, workspace, q, clearance, requiredDistance(true, clearance));
}

bool detail::keepsDistances(const CollisionModel& model, CollisionData& workspace, const robot::JointRef& q,
                            double obstacleRequired, double selfRequired) {
  Workspace& data = detail::workspaceOf(workspace);
  const Implementation& impl = detail::implementationOf(model);
  const auto requiredOf = [&](const Implementation::PairGroup& group) {
    return group.self ? selfRequired : obstacleRequired;
  };
  // The spheres' gaps per pair (a body against its obstacles, then the self pairs) settle most pairs.
  const detail::SpherePrefilter* spheres = impl.prefilter && impl.prefilter->usable() ? impl.prefilter.get() : nullptr;
  const int bodies = spheres != nullptr ? spheres->tables().bodyCount : 0;
  if (spheres != nullptr) {
    if (q.size() != model.robot().dof()) updateRobot(model, data, q);  // throws the usual message
    for (int lane = 0; lane < detail::prefilter::kLanes; ++lane) spheres->loadLane(*data.spheres, lane, q.data());
    // A pair whose coarse spheres clear it by that much needs no fine spheres (sphere_tables.h).
    auto& enough = data.spheres->enough;
    std::fill(enough.begin(), enough.begin() + bodies, static_cast<float>(obstacleRequired + spheres->margin()));
    std::fill(enough.begin() + bodies, enough.end(), static_cast<float>(selfRequired + spheres->margin()));
    // A pair whose floor answers needs no spheres beyond the coarse ones.
    for (int p = 0; p < spheres->tables().selfPairCount; ++p) {
      if (impl.selfGroups[spheres->selfGroupOf(p)].floor >= selfRequired)
        enough[bodies + p] = -detail::prefilter::kFarGap;
    }
    spheres->gaps(*data.spheres);
  }
  const auto settled = [&](int pair, double required) {
    return spheres != nullptr && pair >= 0 &&
           static_cast<double>(data.spheres->gaps[static_cast<std::size_t>(pair) * detail::prefilter::kLanes]) >=
               required;
  };
  data.openPairs.clear();
  bool placed = false;
  for (int k = 0; k < static_cast<int>(impl.groups.size()); ++k) {
    const double required = requiredOf(*impl.groups[k]);
    if (impl.groups[k]->floor >= required) continue;
    if (settled(spheres != nullptr ? spheres->gapPairOfGroup(impl, static_cast<std::size_t>(k)) : -1, required))
      continue;
    if (impl.groups[k]->floorGrid &&
        impl.groups[k]->floorGrid->at(q, &data.pairAxes[impl.firstPartPair[k]]) >= required)
      continue;
    if (!placed) updateRobot(model, data, q);
    placed = true;
    if (!addOpenPairs(model, data, k, required)) return false;
  }
  // A pair in contact answers at once (boolean queries, hulls first, cost a fraction of a distance);
  // else the hulls' distances, and for the pairs they leave open the distances distance() measures.
  const auto parts = [&](const std::pair<int, bool>& open) {
    const auto& pair = impl.partPairs[open.first];
    return std::tie(impl.robotParts[pair.first], data.partPoses[pair.first], secondPart(impl, *pair.group, pair.second),
                    secondPose(impl, data, *pair.group, pair.second));
  };
  // A pair apart by more than required along the direction its last GJK found (separatingGap: vertex projections
  // or a primitive's closed form, a fraction of a GJK) is settled; successive queries of a search are nearby states.
  const auto apartAlongItsAxis = [&](const std::pair<int, bool>& open) {
    const Eigen::Vector3d& axis = data.pairAxes[open.first];
    if (axis.isZero()) return false;
    const auto [a, poseA, b, poseB] = parts(open);
    return detail::separatingGap(a, poseA, b, poseB, axis) - kHullDistanceSlack >=
           requiredOf(*impl.partPairs[open.first].group);
  };
  data.openPairs.erase(std::remove_if(data.openPairs.begin(), data.openPairs.end(), apartAlongItsAxis),
                       data.openPairs.end());
  // A witness point inside the clearance refuses the state before any GJK (a gripper part in or beside a board).
  for (const auto& open : data.openPairs) {
    const auto [a, poseA, b, poseB] = parts(open);
    if (detail::witnessCloser(a, poseA, b, poseB,
                              requiredOf(*impl.partPairs[open.first].group) - detail::kWitnessSlack))
      return false;
  }
  for (const auto& open : data.openPairs) {
    if (!open.second) continue;  // bounding volumes apart: the parts cannot touch
    const auto [a, poseA, b, poseB] = parts(open);
    if (partsCollide(a, poseA, b, poseB, model.options())) return false;
  }
  for (const auto& open : data.openPairs) {
    const auto [a, poseA, b, poseB] = parts(open);
    const double required = requiredOf(*impl.partPairs[open.first].group);
    if (detail::hullGap(a, poseA, b, poseB, model.options(), required, data.pairAxes[open.first]) >= required ||
        detail::containingMeshGap(a, poseA, b, poseB, model.options()) >= required)
      continue;
    if (partsDistance(a, poseA, b, poseB, open.second, model.options(), &data.pairAxes[open.first]) < required)
      return false;
  }
  return true;
}

double clearanceOf(const DistanceReport& report) {
  // A self pair at or beyond kSelfClearance meets every clearance (requiredDistance); one closer limits it.
  return std::min(report.obstacleDistance,
                  report.selfDistance < kSelfClearance ? report.selfDistance : std::numeric_limits<double>::infinity());
}

}  // namespace arcplan::collision
