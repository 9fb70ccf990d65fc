#pragma once
// The clearance a state must keep, relaxed near a start or goal that is itself closer than that
// (docs/collision.md, "Clearance near the endpoints"). One rule for every planner: the OMPL state
// validity checker and motion validator (ompl_validity.h) ask it, benchmarks record it.
//
// A problem asks for clearance c (a suite's `clearance`); certified motions for c_m = max(c, the
// motion check's minimumClearance). An endpoint (start or goal) whose own exact clearance e is
// below c_m but above 0 — a grasp ends a millimetre from the object it grasps — gets an approach
// zone: the states q whose largest robot-point displacement from the endpoint, bounded as the
// certified motion check bounds it (max over robot bodies of Σ_j |q_j − endpoint_j|·D_jL), is at
// most kApproachZoneLength. Inside a zone a state needs min(c, kApproachZoneFraction·e) and a motion
// min(c_m, kApproachZoneFraction·e) (at least the motion check's floor of 1e-5 m); elsewhere c and
// c_m. The motion validator certifies a motion piece by piece (motionPieces: inside a zone the zone's
// motion clearance, elsewhere c_m), so every state of an accepted motion is valid. An endpoint in contact (e <= 0)
// gets no zone: it stays invalid, and callers report it instead of planning.
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::collision {

// L: the Robotiq 85's fingers reach ~5 cm past the object's near face when they enclose it and its base
// is ~8 cm long; a zone in which the gripper can move its farthest point by 10 cm lets it back out of
// the grasp and clear the object by a centimetre (measurements in docs/collision.md).
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
  double endpointClearance = 0.0;  // e [m]: collision::distance(...).minimum() at the endpoint
  double stateClearance = 0.0;     // what a state inside the zone keeps [m]
  double motionClearance = 0.0;    // what a motion touching the zone keeps [m]
};

class EndpointClearance {
public:
  // No zones: every state keeps `clearance`, every motion `motionClearance` (0 and 0: no contact,
  // and the motion check's own minimumClearance).
  EndpointClearance(double clearance = 0.0, double motionClearance = 0.0);
  // Measures each endpoint (dof joints) on `model` and gives the ones with 0 < e < motionClearance a
  // zone. motionClearance is raised to clearance. Throws arcplan::Error for a negative or non-finite
  // clearance, or an endpoint of the wrong size.
  EndpointClearance(const CollisionModel& model, double clearance, double motionClearance,
                    const std::vector<robot::JointVector>& endpoints);

  double clearance() const { return clearance_; }
  double motionClearance() const { return motionClearance_; }
  const std::vector<ApproachZone>& zones() const { return zones_; }
  // The smallest clearance a state may have anywhere (c without zones): `endpoint_clearance_m`.
  double smallestStateClearance() const;

  // Largest displacement bound of any robot point between `endpoint` and q [m] (0 without a model).
  double displacement(const robot::JointRef& endpoint, const robot::JointRef& q) const;
  // The smallest such bound along the straight motion qa -> qb (s in [0, 1]) [m].
  double closestApproach(const robot::JointRef& endpoint, const robot::JointRef& qa, const robot::JointRef& qb) const;

  // The motion qa -> qb in pieces, cut where it enters and leaves each zone: a piece inside a zone
  // keeps the zone's motionClearance, the others motionClearance(). So every state of a motion certified
  // piece by piece keeps what stateClearanceAt asks of it, and so does every part of such a motion: OMPL
  // takes the states and sub-motions of a valid motion as valid (its simplifier makes waypoints of them).
  // Pieces in order, covering [0, 1], neighbours with different clearances.
  std::vector<MotionPiece> motionPieces(const robot::JointRef& qa, const robot::JointRef& qb) const;

  // What the state q must keep [m].
  double stateClearanceAt(const robot::JointRef& q) const;
  // What the motion qa -> qb must keep [m]: the smallest requirement of the zones it touches, else
  // motionClearance().
  double motionClearanceAlong(const robot::JointRef& qa, const robot::JointRef& qb) const;

private:
  // The s in [0, 1] where the displacement from `endpoint` along qa -> qb is smallest.
  double nearestFraction(const robot::JointRef& endpoint, const robot::JointRef& qa, const robot::JointRef& qb) const;

  double clearance_, motionClearance_;
  std::vector<ApproachZone> zones_;
  Eigen::MatrixXd reach_;  // bodies × joints: D_jL of the certified motion check (motion_bounds.h)
};

}  // namespace arcplan::collision
