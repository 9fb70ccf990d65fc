#pragma once
// The clearance a state must keep, relaxed near a start or goal that is itself closer than that
// (docs/collision.md, "Clearance near the endpoints"). One rule for every planner: the OMPL state
// validity checker and motion validator (ompl_validity.h) ask it, the arc planner's path checks and
// benchmarks' clearance judgement too.
//
// A problem asks for clearance c (a suite's `clearance`); certified motions for c_m = max(c, the
// motion check's minimumClearance). Each pair keeps what its kind asks of a clearance (requiredDistance,
// collision_model.h: c from obstacles, min(c, kSelfClearance) between the robot's own bodies). An endpoint
// (start or goal) with a pair above 0 but below what a certified motion can end at (that pair's m at c_m
// plus the motion check's acceptance margin) gets an approach zone, e being the closest such pair or the
// endpoint's own exact clearance (clearanceOf), whichever is smaller: the states q in which no point of the robot is
// farther than kApproachZoneLength from where it is at the endpoint. That displacement is measured on the robot's
// geometry moved by forward kinematics (each body by the vertices of its parts' convex hulls — coarse containing hulls,
// a few millimetres larger, where a mesh's hull has many —, spheres and cylinders by their bounding
// capsules): exact for rigid bodies up to those millimetres, where the certified motion check's bound
// (Σ_j |Δq_j|·D_jL) overestimates multi-joint motions 3-5 times. Inside a zone a state needs
// min(c, kApproachZoneFraction·e) and a motion min(c_m, kApproachZoneFraction·e) (at least the motion
// check's floor of 1e-5 m), self pairs the same rule's min(that, kSelfClearance); elsewhere c and c_m. The motion
// validator certifies a motion piece by piece (motionPieces: the zone's motion clearance only on parts proven inside
// the zone, elsewhere c_m), so every state of an accepted motion keeps what stateClearanceAt asks of it. An endpoint in
// contact (e <= 0) gets no zone: it stays invalid, and callers report it instead of planning.
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::collision {

namespace detail {
struct ZoneGeometry;  // endpoint_clearance.cpp: the robot's bodies as points, the endpoints' link poses
}  // namespace detail

// L: the Robotiq 85's fingers reach ~5 cm past the object's near face when they enclose it and its base
// is ~8 cm long; a zone in which no point of the gripper moves more than 10 cm lets it back out of the
// grasp and clear the object by a centimetre (measurements in docs/collision.md).
inline constexpr double kApproachZoneLength = 0.10;  // m
// Zone states keep half of the endpoint's own clearance: the way in may pass a little closer than the
// endpoint (fingers sliding past an edge), and the endpoint never sits exactly on its own limit.
inline constexpr double kApproachZoneFraction = 0.5;

// A part [from, to] of a motion (fractions of it, 0 at its start) and the clearance it keeps [m].
struct MotionPiece {
  double from = 0.0, to = 1.0;
  double clearance = 0.0;
};

struct ApproachZone {
  robot::JointVector endpoint;
  double endpointClearance = 0.0;  // e [m]: clearanceOf at the endpoint, or a closer self pair no motion leaves
  double stateClearance = 0.0;     // what a state inside the zone keeps [m]
  double motionClearance = 0.0;    // what a motion inside the zone keeps [m]
};

class EndpointClearance {
public:
  // No zones: every state keeps `clearance`, every motion `motionClearance` (0 and 0: no contact,
  // and the motion check's own minimumClearance).
  EndpointClearance(double clearance = 0.0, double motionClearance = 0.0);
  // Measures each endpoint (dof joints) on `model` and gives the ones with 0 < e < motionClearance +
  // the motion check's acceptance margin a zone. motionClearance is raised to clearance. Throws
  // arcplan::Error for a negative or non-finite clearance, or an endpoint of the wrong size.
  EndpointClearance(const CollisionModel& model, double clearance, double motionClearance,
                    const std::vector<robot::JointVector>& endpoints);

  double clearance() const { return clearance_; }
  double motionClearance() const { return motionClearance_; }
  const std::vector<ApproachZone>& zones() const { return zones_; }
  // The smallest clearance a state may have anywhere (c without zones): `endpoint_clearance_m`.
  double smallestStateClearance() const;

  // The motion qa -> qb in pieces: a piece proven inside a zone (every state of it within
  // kApproachZoneLength of the endpoint) keeps the zone's motionClearance, the others motionClearance().
  // So every state of a motion certified piece by piece keeps what stateClearanceAt asks of it: OMPL
  // takes the states of a valid motion as valid (its simplifier makes waypoints of them). Pieces in
  // order, covering [0, 1], neighbours with different clearances.
  std::vector<MotionPiece> motionPieces(const robot::JointRef& qa, const robot::JointRef& qb) const;

  // What the state q must keep [m].
  double stateClearanceAt(const robot::JointRef& q) const;
  // What a motion ending (or starting) at q must keep there [m]: its zone's motionClearance wherever
  // stateClearanceAt gives it the zone's stateClearance, else motionClearance(). A motion's own
  // requirement is piece by piece (motionPieces): never the smallest of its pieces for all of it.
  double motionClearanceAt(const robot::JointRef& q) const;

private:
  // Whether q lies in the zone of endpoint `zone`; q's link poses are computed into `poses` on first need.
  bool inZone(std::size_t zone, const robot::JointRef& q, std::optional<robot::KinematicsData>& poses) const;
  // The parts of [0, 1] of qa -> qb proven inside zone `zone`, in order and disjoint.
  std::vector<std::pair<double, double>> insideParts(std::size_t zone, const robot::JointRef& qa,
                                                     const robot::JointRef& qb) const;

  double clearance_, motionClearance_;
  std::vector<ApproachZone> zones_;
  std::shared_ptr<const detail::ZoneGeometry> geometry_;  // null without zones
};

}  // namespace arcplan::collision
