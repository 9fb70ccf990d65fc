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
    text << "closer than the " << margin << " m clearance (" << pairsText(pairs) << " at " << closest
         << " m)";
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
  JointWaypoints continuation = convertToJoints(ik_, path, prefix.joints.back(), goal, conversion_,
                                                prefix.arcLengths.back(), std::numeric_limits<double>::infinity(), check);
  JointWaypoints combined = prefix;
  combined.joints.insert(combined.joints.end(), continuation.joints.begin() + 1, continuation.joints.end());
  combined.arcLengths.insert(combined.arcLengths.end(), continuation.arcLengths.begin() + 1,
                             continuation.arcLengths.end());
  combined.status = continuation.status;
  combined.reason = continuation.reason;
  combined.failedAtArcLength = continuation.failedAtArcLength;
  return combined;
}

Rejection PathValidator::rejection() {
  // 16 states along the rejected motion: its end first (usually where the contact is).
  constexpr int kSteps = 16;
  const auto along = [&](int k) -> robot::Vector6 {
    return rejectedPrevious_ + (rejectedJoints_ - rejectedPrevious_) * (static_cast<double>(k) / kSteps);
  };
  Rejection result;
  result.pairs = collision::collide(model_, data_, rejectedJoints_);
  for (int k = 0; k < kSteps && result.pairs.valid; ++k) result.pairs = collision::collide(model_, data_, along(k));
  if (!result.pairs.valid) return result;
  result.collides = false;
  result.closest = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= kSteps; ++k) {
    const collision::DistanceReport d = collision::distance(model_, data_, along(k));
    if (d.minimum() < result.closest) {
      result.closest = d.minimum();
      result.pairs.collisions = {d.obstacleDistance <= d.selfDistance ? d.obstaclePair : d.selfPair};
    }
  }
  return result;
}

}  // namespace arcplan::planners
