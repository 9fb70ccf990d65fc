#pragma once
// Validating a TCP path for the whole robot while converting it to joints (cartesian_to_joint.h):
// certified, every motion between consecutive waypoints proven to keep `margin` from obstacles and
// between links (collision::PathCertifier, the check of the SpaceInformation's motion validator), or
// only the waypoints themselves (a caller's state check, as MoveIt's Cartesian paths do). A walk
// stops at the first waypoint that fails and says which bodies were behind it.
#include <functional>
#include <string>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/planners/cartesian_to_joint.h"

namespace arcplan::planners {

// Why a walk stopped at a waypoint: the pairs in contact at the rejected waypoint, else its closest
// pair when that is closer than the margin; only when the waypoint itself keeps the margin, the
// pairs in contact along the motion to it, else the closest pair along that motion.
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
  // Certified with `margin` when `certify`, else every waypoint by `waypointValid`. `stop` (the
  // planner's termination condition) rejects the next waypoint once it returns true.
  PathValidator(const collision::CollisionModel& model, const robot::UrInverseKinematics& ik,
                JointConversionOptions conversion, double margin, bool certify, StateCheck waypointValid,
                StopRequest stop);

  // Continues the validated `prefix` (at least the start configuration) along `path` to its end,
  // where `goal` (if given) must be met; stops at the first waypoint that fails. Returns prefix +
  // continuation, with the status and reason of the conversion.
  JointWaypoints walk(const TcpPath& path, const JointWaypoints& prefix, const std::optional<robot::Vector6>& goal);
  // One configuration tested on its own, without a walk up to it: false when it is closer than the
  // margin to an obstacle or between links, and rejection() then explains it. A cheap test of where
  // a path is likely to fail before the walk; a configuration that passes proves nothing about the
  // motions around it.
  bool keepsMargin(const robot::Vector6& q);
  // The rejection behind the last walk's failure (status Rejected) or the last failed keepsMargin.
  Rejection rejection();
  double margin() const { return margin_; }

private:
  bool validMotion(const robot::Vector6& previous, const robot::Vector6& q);

  const collision::CollisionModel& model_;
  const robot::UrInverseKinematics& ik_;
  JointConversionOptions conversion_;
  double margin_;
  bool certify_;
  StateCheck waypointValid_;
  StopRequest stop_;
  collision::CollisionData data_;
  std::optional<collision::PathCertifier> certifier_;  // of the current walk
  robot::Vector6 rejectedPrevious_ = robot::Vector6::Zero(), rejectedJoints_ = robot::Vector6::Zero();
};

}  // namespace arcplan::planners
