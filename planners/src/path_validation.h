#pragma once
// Validating a TCP path for the whole robot while converting it to joints (cartesian_to_joint.h):
// certified, every motion between consecutive waypoints proven to keep the clearance the endpoint rule
// asks of it, piece by piece (collision::EndpointClearance::motionPieces: the margin, or inside an
// approach zone the zone's less near a start or goal closer than that; collision::PathCertifier, the check of the
// SpaceInformation's motion validator), or
// only the waypoints themselves (a caller's state check, as MoveIt's Cartesian paths do). A walk
// stops at the first waypoint that fails and returns the motion it refused; explain() names the
// bodies behind it. Internal to the arc planner.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/endpoint_clearance.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/planners/cartesian_to_joint.h"

namespace arcplan::planners {

// Waypoints between two the screen tests (1 cm apart at the default resolution): a place where a path comes too
// close is rarely shorter than 3 cm, and one the screen steps over is still found by the certified walk.
inline constexpr int kScreenStride = 3;
// m below a motion's clearance that the screen refuses: distances computed for the same pair by hasClearance and
// by a certificate may differ by rounding, and the screen must never refuse what the certificate accepts.
inline constexpr double kScreenTolerance = 1e-6;

// The motion a walk stopped at: from its last accepted waypoint to the one refused (both the same
// configuration when one was tested on its own, as keepsMargin does).
struct RejectedMotion {
  robot::Vector6 from = robot::Vector6::Zero();
  robot::Vector6 to = robot::Vector6::Zero();
};

// What a walk validated, and where it stopped when it did not reach the end.
struct Walk {
  JointConversionResult waypoints;         // the prefix, continued up to where the walk stopped (screen: the prefix)
  std::optional<RejectedMotion> rejected;  // status Rejected: the motion refused (also when the stop request ended it)

  bool ok() const { return waypoints.ok(); }
};

// Why a motion was rejected: the pairs in contact at its end, else its pair nearest to what the certificate accepts
// (its own m, collision::requiredDistance, plus the acceptance margin) when that is closer (a pair the certificate
// may refuse); only when the end itself keeps that, the pairs in contact along the motion, else the pair nearest to
// it along the motion.
struct Rejection {
  collision::CollisionReport pairs;
  bool collides = true;
  double closest = 0.0;  // m, when it does not collide

  bool involves(const std::string& body) const;
  std::string describe(double margin) const;
};

class PathValidator {
public:
  using StateCheck = std::function<bool(const robot::Vector6&)>;
  using StopRequest = std::function<bool()>;
  // Certified by `required` (every motion piece by piece, motionPieces; a motion in an approach zone also
  // checks that its end keeps stateClearanceAt) when `certify`, else every waypoint by `waypointValid`.
  // `stop` (the planner's termination condition) rejects the next waypoint once it returns true.
  PathValidator(const collision::CollisionModel& model, const robot::UrInverseKinematics& ik,
                JointConversionOptions conversion, collision::EndpointClearance required, bool certify,
                StateCheck waypointValid, StopRequest stop);
  // The same with `margin` for every state and motion (no approach zones).
  PathValidator(const collision::CollisionModel& model, const robot::UrInverseKinematics& ik,
                JointConversionOptions conversion, double margin, bool certify, StateCheck waypointValid,
                StopRequest stop);

  // Continues the validated `prefix` (at least the start configuration) along `path` to its end,
  // where `goal` (if given) must be met; stops at the first waypoint that fails. Returns prefix +
  // continuation, with the status and reason of the conversion and the motion it refused.
  // `converted`, when given and not empty, is the conversion screen() left for the same path, prefix and goal: the
  // walk then checks its waypoints without solving the IK again (checkConverted; the same walk).
  Walk walk(const TcpPath& path, const JointConversionResult& prefix, const std::optional<robot::Vector6>& goal,
            const JointConversionResult* converted = nullptr);
  // A walk's cheap forerunner: the path converted to joints (IK only, up to the waypoint refused), every
  // kScreenStride-th waypoint (and the last) tested on its own by withinMargin and refuses() (and, after the first it
  // refuses, the ones before it by withinMargin, going back while they are within it). A waypoint it refuses fails
  // every certified walk there or before, so the walk need not be paid for: returned as a walk rejected there — or at
  // the first of the waypoints just before it that are all withinMargin, where the walk would stop — its waypoints only
  // `prefix` (nothing after it was certified), the motion refused the one to that waypoint. Nothing when no tested
  // waypoint is refused, when a tested waypoint before the refused one came within the margin and a later one left it
  // (the walk may stop there already), or once `stop` returns true: the walk decides then. `conversion` (if given)
  // receives the path's conversion (IK only), or is left empty where nothing is screened.
  std::optional<Walk> screen(const TcpPath& path, const JointConversionResult& prefix,
                             const std::optional<robot::Vector6>& goal, JointConversionResult* conversion = nullptr);
  // True when a pair at q is closer than a motion ending at q must keep of it (collision::requiredDistance)
  // (EndpointClearance::motionClearanceAt: its approach zone's clearance, else the margin), less kScreenTolerance: so
  // certainly that no certified motion reaches q (collision::hasClearance, whose bounds settle pairs far apart; a
  // certificate's measurements cost more).
  bool refuses(const robot::Vector6& q);
  // True when a pair at q is closer than a motion ending there must keep of it plus the certificate's acceptance
  // margin (collision::keepsAcceptanceMargin, motion_check.h): where a certified walk may already stop.
  bool withinMargin(const robot::Vector6& q);
  // One configuration tested on its own, without a walk up to it: false when it is closer than a
  // motion from it must keep (the margin, or its approach zone's; per pair, collision::requiredDistance) (explain({q,
  // q}) says why). A cheap test of where a path is likely to fail before the walk; a configuration that passes proves
  // nothing about the motions around it.
  bool keepsMargin(const robot::Vector6& q);
  // The bodies behind a refused motion (collision and distance queries: asked only when needed).
  Rejection explain(const RejectedMotion& motion);
  // The clearance of motions away from the endpoints' approach zones.
  double margin() const { return required_.motionClearance(); }

private:
  const collision::CollisionModel& model_;
  const robot::UrInverseKinematics& ik_;
  JointConversionOptions conversion_;
  collision::EndpointClearance required_;
  bool certify_;
  StateCheck waypointValid_;
  StopRequest stop_;
  collision::CollisionData data_;
};

}  // namespace arcplan::planners
