#include "arcplan/planners/path_validation.h"

#include <algorithm>
#include <limits>
#include <sstream>

namespace arcplan::planners {

namespace {

// A rejection without a named pair was between two waypoints.
std::string pairsText(const collision::CollisionReport& report) {
  const std::string text = collision::describeCollisions(report);
  return text.empty() ? "between two waypoints" : text;
}

}  // namespace

bool Rejection::involves(const std::string& body) const {
  return std::any_of(pairs.collisions.begin(), pairs.collisions.end(),
                     [&](const collision::NamePair& pair) { return pair.first == body || pair.second == body; });
}

std::string Rejection::describe(double margin) const {
  std::ostringstream text;
  if (collides) {
    text << "collision (" << pairsText(pairs) << ")";
  } else {
    text << "closer than the " << margin << " m clearance (" << pairsText(pairs) << " at " << closest << " m)";
  }
  return text.str();
}

PathValidator::PathValidator(const collision::CollisionModel& model, const robot::UrInverseKinematics& ik,
                             JointConversionOptions conversion, double margin, bool certify, StateCheck waypointValid,
                             StopRequest stop)
    : model_(model),
      ik_(ik),
      conversion_(conversion),
      margin_(margin),
      certify_(certify),
      waypointValid_(std::move(waypointValid)),
      stop_(std::move(stop)),
      data_(model) {}

bool PathValidator::validMotion(const robot::Vector6& previous, const robot::Vector6& q) {
  if (!certify_) return waypointValid_(q);
  // One certifier per walk, started at the walk's first configuration: it reuses a waypoint's
  // measured clearance for the following motions, so it must never carry over from another path.
  if (!certifier_) {
    certifier_.emplace(model_, data_, margin_);
    if (!certifier_->start(previous)) return false;
  }
  return certifier_->extend(q);
}

JointWaypoints PathValidator::walk(const TcpPath& path, const JointWaypoints& prefix,
                                   const std::optional<robot::Vector6>& goal) {
  certifier_.reset();
  const WaypointCheck check = [this](const robot::Vector6& previous, const robot::Vector6& q, double) {
    if (stop_ && stop_()) return false;
    if (validMotion(previous, q)) return true;
    rejectedPrevious_ = previous;
    rejectedJoints_ = q;
    return false;
  };
  JointWaypoints continuation =
      convertToJoints(ik_, path, prefix.joints.back(), goal, conversion_, prefix.arcLengths.back(),
                      std::numeric_limits<double>::infinity(), check);
  JointWaypoints combined = prefix;
  combined.joints.insert(combined.joints.end(), continuation.joints.begin() + 1, continuation.joints.end());
  combined.arcLengths.insert(combined.arcLengths.end(), continuation.arcLengths.begin() + 1,
                             continuation.arcLengths.end());
  combined.status = continuation.status;
  combined.reason = continuation.reason;
  combined.failedAtArcLength = continuation.failedAtArcLength;
  return combined;
}

bool PathValidator::keepsMargin(const robot::Vector6& q) {
  // A certifier's start: the same test as a walk's first waypoint, with pairs far apart settled by
  // their bounding capsules (cheaper than measuring the smallest distance).
  if (collision::PathCertifier(model_, data_, margin_).start(q)) return true;
  rejectedPrevious_ = q;
  rejectedJoints_ = q;
  return false;
}

Rejection PathValidator::rejection() {
  Rejection result;
  result.pairs = collision::collide(model_, data_, rejectedJoints_);
  if (!result.pairs.valid) return result;  // contact at the rejected waypoint (the usual case)
  result.collides = false;
  const auto closestPair = [](const collision::DistanceReport& d) {
    return d.obstacleDistance <= d.selfDistance ? d.obstaclePair : d.selfPair;
  };
  // Closer than the margin at the rejected waypoint: that pair is the reason, one query suffices
  // (the route search asks this for every rejected route).
  const collision::DistanceReport atWaypoint = collision::distance(model_, data_, rejectedJoints_);
  result.closest = atWaypoint.minimum();
  result.pairs.collisions = {closestPair(atWaypoint)};
  if (result.closest < margin_) return result;
  // The waypoint keeps the margin but the motion to it could not be certified: 16 states along it.
  constexpr int kSteps = 16;
  const auto along = [&](int k) -> robot::Vector6 {
    return rejectedPrevious_ + (rejectedJoints_ - rejectedPrevious_) * (static_cast<double>(k) / kSteps);
  };
  for (int k = 0; k < kSteps; ++k) {
    const collision::CollisionReport contact = collision::collide(model_, data_, along(k));
    if (!contact.valid) {
      result.pairs = contact;
      result.collides = true;
      return result;
    }
  }
  for (int k = 0; k < kSteps; ++k) {
    const collision::DistanceReport d = collision::distance(model_, data_, along(k));
    if (d.minimum() < result.closest) {
      result.closest = d.minimum();
      result.pairs.collisions = {closestPair(d)};
    }
  }
  return result;
}

}  // namespace arcplan::planners
