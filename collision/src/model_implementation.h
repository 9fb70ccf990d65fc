#pragma once
// CollisionModel's and CollisionData's internals, shared by the per-state queries
// (collision_model.cpp) and the motion checks (motion_check.cpp): the parts, the non-allowed pair
// groups, the motion bounds, the per-thread workspace, and the building blocks of a query (forward
// kinematics, bounding-volume gaps, exact part distances).
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "arcplan/collision/collision_model.h"
#include "parts.h"

namespace arcplan::collision::detail {

class SpherePrefilter;  // sphere_prefilter.h
class PairFloorGrid;    // pair_floor_grid.h
struct SphereWorkspace;

// GJK's distances are exact to about 1e-6 m (docs/collision.md); a hull's (or containing mesh's)
// distance is taken this much smaller, so that as a lower bound it never rests on an overestimate.
inline constexpr double kHullDistanceSlack = 1e-6;

// Robot parts move with their link; obstacle parts are fixed in base_link, so their bounding
// volumes are precomputed in world coordinates.
struct ModelImplementation {
  std::vector<detail::Part> robotParts;  // Part::body indexes linkNames()
  std::vector<int> robotPartLink;        // index into robot().links(), for forward kinematics
  // Per link with geometry (indexed like linkNames()): a capsule around all its parts, in the link
  // frame, so far-apart link pairs are dismissed with one test instead of one per part pair.
  std::vector<detail::Capsule> linkCapsules;
  std::vector<int> linkCapsuleLink;
  std::vector<detail::Part> obstacleParts;  // Part::body indexes obstacleNames(), Part::offset is the world pose
  std::vector<Eigen::Vector3d> obstacleCapsuleStarts, obstacleCapsuleEnds;
  std::vector<Eigen::Isometry3d> obstacleInversePoses;

  // Motion bounds (motion_bounds.cpp), per link with geometry b and joint j: movedBy(b, j) when j
  // is an ancestor joint of b, and then jointReach(b, j) >= the distance of every point of b's
  // geometry from j's axis in every configuration (0 otherwise).
  Eigen::MatrixXd jointReach;
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> movedBy;

  // The parts of one non-allowed body pair; `second` is an obstacle part for robot–obstacle groups.
  struct PairGroup {
    int firstBody = -1, secondBody = -1;
    bool self = false;
    std::vector<std::pair<int, int>> parts;
    std::vector<int> obstacleParts;  // the second body's parts (robot–obstacle groups)
    // On a straight joint motion with steps dq the pair's distance shrinks at most by
    // relativeReach · |dq| (motion_check.cpp).
    Eigen::VectorXd relativeReach;
    // A self pair no joint moves apart (both bodies on the same rigid end, e.g. a gripper's fingers and
    // its base): its distance never changes, so it is measured once, when the model is built.
    bool rigid = false;
    bool rigidCollides = false;
    double rigidDistance = 0.0;
    // A lower bound of the pair's distance in every configuration (0: none known). A self pair that one
    // joint alone turns against each other (MBM's force sensor on wrist 3 against wrist 2) has a distance
    // that depends on that joint only: its smallest value over the joint's range is measured when the
    // model is built (measurePairFloors), and no query measures the pair while its floor answers.
    double floor = 0.0;
    // A self pair that two joints alone move against each other: floors per cell of the two angles (pair_floor_grid.h;
    // null otherwise). Shared with other models of the same robot.
    std::shared_ptr<const PairFloorGrid> floorGrid = nullptr;
    // What a clearance c asks of this pair (requiredDistance, collision_model.h).
    double required(double clearance) const { return requiredDistance(self, clearance); }
  };
  std::vector<PairGroup> obstacleGroups, selfGroups;
  std::vector<const PairGroup*> groups;  // obstacle groups, then self groups
  // Every part pair of every group, for distance queries (which order them by their bounds).
  struct PartPair {
    const PairGroup* group;
    int first, second;
  };
  std::vector<PartPair> partPairs;
  std::vector<int> firstPartPair;  // per group of `groups`: where its part pairs start in partPairs
  // Per part pair (partPairs order), the group's relativeReach with the two parts' own reaches.
  Eigen::MatrixXd partPairReach;
  // The SIMD sphere prefilter in front of FCL (null with CollisionModelOptions::spherePrefilter off).
  std::shared_ptr<const SpherePrefilter> prefilter;
};

using Implementation = ModelImplementation;

// What CollisionData holds: link poses, the world poses of the robot's parts and their bounding capsules.
struct Workspace {
  explicit Workspace(const CollisionModel& model);
  robot::KinematicsData kinematics;
  std::vector<Eigen::Isometry3d> partPoses;
  std::vector<Eigen::Vector3d> capsuleStarts, capsuleEnds;  // per part
  // Part poses and capsules are computed when a query first needs them: valid for the current
  // configuration where partStamps[i] == stamp (incremented by every query).
  std::vector<std::uint64_t> partStamps;
  std::uint64_t stamp = 0;
  std::vector<Eigen::Vector3d> linkCapsuleStarts, linkCapsuleEnds;  // per link with geometry
  std::vector<std::pair<double, int>> distanceOrder;                // (lower bound, pair) for distance queries
  // hasClearance: the part pairs its bounds leave open (index into partPairs, bounding volumes overlap).
  std::vector<std::pair<int, bool>> openPairs;
  // Motion checks (motion_check.h): per non-allowed body pair, how fast its distance can shrink
  // along the motion [m per unit of the motion's fraction], the fractions before / after which it is
  // proven apart, and where those certificates were measured.
  struct MotionPair {
    double rate = 0.0;
    double certifiedFromStart = 0.0, certifiedFromEnd = 1.0;
    double measuredFromStart = 0.0, measuredFromEnd = 1.0;
  };
  std::vector<MotionPair> motionPairs;
  std::vector<int> activePairs;  // the groups (indices of motionPairs) not yet certified over the motion
  // Per part pair (ModelImplementation::partPairs): the direction from the first part's hull to the second's that
  // GJK found at its last measurement in this workspace, in the first part's frame; zero before (hullGap). The
  // certified motion check takes only those found during the same motion (pairAxisMotions[pair] == motion), so
  // that where it measures depends on the motion alone, never on earlier queries; state checks take any (their
  // answers are the exact ones whichever bound proves a pair apart).
  std::vector<Eigen::Vector3d> pairAxes;
  std::vector<std::uint64_t> pairAxisMotions;
  std::uint64_t motion = 0;         // certified motion checks begun in this workspace
  robot::JointVector motionJoints;  // the configuration on the motion being checked
  robot::JointVector probeJoints;   // a state probed before advancing (motion_check.cpp)
  // Motion checks: a group's part pairs with their capsule bounds, in the order they are measured.
  struct OrderedPart {
    double key, bound;
    int part;
  };
  std::vector<OrderedPart> partOrder;
  std::shared_ptr<SphereWorkspace> spheres;  // the prefilter's scratch (null without a prefilter)
};

// Forward kinematics and the link capsules; part poses are computed on first use (ensurePart), so
// a state whose links are far from everything never transforms its parts.
void updateRobot(const CollisionModel& model, Workspace& data, const robot::JointRef& q);

inline void ensurePart(const Implementation& impl, Workspace& data, int i) {
  if (data.partStamps[i] == data.stamp) return;
  const Part& part = impl.robotParts[i];
  data.partPoses[i] = data.kinematics.linkPoses[impl.robotPartLink[i]] * part.offset;
  data.capsuleStarts[i] = data.partPoses[i] * part.capsule.start;
  data.capsuleEnds[i] = data.partPoses[i] * part.capsule.end;
  data.partStamps[i] = data.stamp;
}

// Lower bound of the distance between a capsule (segment start-end, radius) and obstacle part j.
inline double obstacleGap(const Implementation& impl, const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                          double radius, int j) {
  const Part& obstacle = impl.obstacleParts[j];
  if (obstacle.boxBound) {
    const Eigen::Isometry3d& toBox = impl.obstacleInversePoses[j];
    return capsuleBoxLowerBound(toBox * start, toBox * end, radius, obstacle.boxHalfExtents);
  }
  return segmentDistance(start, end, impl.obstacleCapsuleStarts[j], impl.obstacleCapsuleEnds[j]) - radius -
         obstacle.capsule.radius;
}

// Lower bound of the distance between robot part i and part j (robot part if `self`, else obstacle
// part) from their bounding volumes; <= 0 when the volumes overlap.
inline double boundGap(const Implementation& impl, Workspace& data, int i, int j, bool self) {
  ensurePart(impl, data, i);
  const double radius = impl.robotParts[i].capsule.radius;
  if (!self) return obstacleGap(impl, data.capsuleStarts[i], data.capsuleEnds[i], radius, j);
  ensurePart(impl, data, j);
  return segmentDistance(data.capsuleStarts[i], data.capsuleEnds[i], data.capsuleStarts[j], data.capsuleEnds[j]) -
         radius - impl.robotParts[j].capsule.radius;
}

// Lower bound of the distance between the group's two bodies from the capsule around its link
// (and the obstacle parts' bounds); <= 0 when they overlap.
double linkGap(const Implementation& impl, const Workspace& data, const Implementation::PairGroup& group);

// Distance between two parts (0 when they touch or one is inside the other). With `axis`, where GJK runs on the
// parts themselves (convex parts, CollisionModelOptions::convexDistance), the direction between its nearest points is
// kept there (in a's frame, as hullGap keeps it; left as it was where they touch).
double partsDistance(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
                     bool boundsOverlap, const CollisionModelOptions& options, Eigen::Vector3d* axis = nullptr);

// A lower bound of partsDistance(a, b) from the parts' hulls (GJK, less its tolerance): 0 when the
// hulls touch, when the layer is off, or when partsDistance would run GJK on the parts themselves.
// The coarse hulls' bound is returned when it reaches `enough` (the caller's threshold), else the hulls'.
double hullGap(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
               const CollisionModelOptions& options, double enough);
// hullGap of the part pair measured again and again (Workspace::pairAxes[pair]): first the bound along the direction
// GJK found last time (separatingGap), returned when it reaches `enough`; else hullGap, whose GJK leaves its direction
// (convex parts: 0, as above; partsDistance with the axis measures them and leaves its direction).
double hullGap(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
               const CollisionModelOptions& options, double enough, Eigen::Vector3d& axis);
// The largest projection on `direction` (in the part's frame) of the part's hull (the vertices of an fcl::Convex hull,
// closed-form for a box, sphere or cylinder); +infinity for a part without one.
double supportAlong(const Part& part, const Eigen::Vector3d& direction);
// A lower bound of the distance of two convex hulls from any direction n (unit, a's frame, pointing from a to b):
// min over b's hull of n·x − max over a's of n·x (their support functions: the vertices of an fcl::Convex hull,
// closed-form for a box, sphere or cylinder), −infinity where a part has neither.
double separatingGap(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
                     const Eigen::Vector3d& axisInA);

// A lower bound of partsDistance(a, b) for a primitive against a mesh part from the primitive's
// containing mesh (Part::containingMesh; triangle distances, less GJK's tolerance), at most the
// containing mesh's largest gap below it: 0 when they touch, when the layer (hullLayer) is off, or for
// other pairs. Asked after hullGap, where the hull (convex) is loose: a can held between finger tips.
double containingMeshGap(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
                         const CollisionModelOptions& options);

// Whether a witness point of robot part a lies closer than `distance` to obstacle b: one of Part::witnessPoints to
// a box (Part::boxBound), any vertex (Part::hullPoints) to a cylinder or sphere. A point pair's distance bounds the
// parts' from above, so they are closer too. False for other obstacles. Callers ask it for `distance` kWitnessSlack
// below a threshold that an exact distance would decide: GJK's 1e-6 m error can then not make that distance come out on
// the other side, and the answer stays the exact one.
bool witnessCloser(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
                   double distance);
inline constexpr double kWitnessSlack = 1e-5;

// The group's part pairs' entries of Workspace::pairAxes (what a floor grid keeps between its cells).
inline Eigen::Vector3d* groupAxes(const Implementation& impl, Workspace& data, const Implementation::PairGroup& group) {
  const std::size_t first = group.self ? impl.obstacleGroups.size() + (&group - impl.selfGroups.data())
                                       : static_cast<std::size_t>(&group - impl.obstacleGroups.data());
  return &data.pairAxes[impl.firstPartPair[first]];
}

inline const Part& secondPart(const Implementation& impl, const Implementation::PairGroup& group, int j) {
  return group.self ? impl.robotParts[j] : impl.obstacleParts[j];
}

inline const Eigen::Isometry3d& secondPose(const Implementation& impl, const Workspace& data,
                                           const Implementation::PairGroup& group, int j) {
  return group.self ? data.partPoses[j] : impl.obstacleParts[j].offset;
}

// Whether at q every robot–obstacle pair is at least obstacleRequired and every self pair at least selfRequired
// apart (both > 0): hasClearance with the distances given per kind (collision_model.cpp).
bool keepsDistances(const CollisionModel& model, CollisionData& workspace, const robot::JointRef& q,
                    double obstacleRequired, double selfRequired);

// The pair group at q whose exact distance less an offset per kind (obstacle pairs, self pairs) is least, that
// distance and the difference; an obstacle pair before a self pair as far. distance()'s part-pair order and bounds, but
// one running best over both kinds: a pair whose bound less its offset is above it is never measured
// (collision_model.cpp).
struct LeastPair {
  const ModelImplementation::PairGroup* group = nullptr;
  double distance = std::numeric_limits<double>::infinity();
  double value = std::numeric_limits<double>::infinity();
};
LeastPair leastOffsetPair(const CollisionModel& model, CollisionData& workspace, const robot::JointRef& q,
                          double obstacleOffset, double selfOffset);

// The group's two bodies by name: (link, obstacle) or (link, link) (collision_model.cpp).
NamePair namesOf(const CollisionModel& model, const ModelImplementation::PairGroup& group);

// Whether the group's bodies touch in the current configuration (updateRobot) (collision_model.cpp).
bool groupCollides(const CollisionModel& model, Workspace& data, const ModelImplementation::PairGroup& group);

// Measures the self pairs whose relativeReach is 0 once and marks them rigid (collision_model_building.cpp).
void measureRigidPairs(const CollisionModel& model, ModelImplementation& impl);
// PairGroup::floor of the self pairs one joint alone moves against each other, PairGroup::floorGrid of those two
// joints move (pair_floors.cpp).
void measurePairFloors(const CollisionModel& model, ModelImplementation& impl);

// Fills impl.jointReach, impl.movedBy, impl.partPairReach and every group's relativeReach (motion_bounds.cpp).
void computeMotionBounds(const robot::RobotModel& robot, Implementation& impl);

}  // namespace arcplan::collision::detail
