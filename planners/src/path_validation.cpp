#include "path_validation.h"

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
                             JointConversionOptions conversion, collision::EndpointClearance required, bool certify,
                             StateCheck waypointValid, StopRequest stop)
    : model_(model),
      ik_(ik),
      conversion_(conversion),
      required_(std::move(required)),
      certify_(certify),
      waypointValid_(std::move(waypointValid)),
      stop_(std::move(stop)),
      data_(model) {}

PathValidator::PathValidator(const collision::CollisionModel& model, const robot::UrInverseKinematics& ik,
                             JointConversionOptions conversion, double margin, bool certify, StateCheck waypointValid,
                             StopRequest stop)
    : PathValidator(model, ik, conversion, collision::EndpointClearance(margin, margin), certify,
                    std::move(waypointValid), std::move(stop)) {}

Walk PathValidator::walk(const TcpPath& path, const JointConversionResult& prefix,
                         const std::optional<robot::Vector6>& goal, const JointConversionResult* converted) {
  // One certifier per walk and clearance, started at the motion's first configuration: it reuses a
  // waypoint's measured clearance for the following motions, so it must never carry over from another
  // path, nor to a motion that must keep another clearance (entering or leaving an approach zone).
  std::optional<collision::PathCertifier> certifier;
  double certifierClearance = 0.0;
  // A converted path's waypoints are known before the walk: its certifiers expect them (from the motion's start on),
  // so the spheres measure 8 at a time.
  const bool known = converted != nullptr && !converted->joints.empty();
  const Eigen::Map<const Eigen::MatrixXd> waypoints(known ? converted->joints.front().data() : nullptr,
                                                    robot::Vector6::RowsAtCompileTime,
                                                    known ? static_cast<Eigen::Index>(converted->joints.size()) : 0);
  Eigen::Index nextWaypoint = 1;  // the column of waypoints the check is asked next (checkConverted's order)
  const WaypointCheck check = [&](const robot::Vector6& from, const robot::Vector6& q, double) {
    if (stop_ && stop_()) return false;
    if (!certify_) return waypointValid_(q);
    const Eigen::Index waypoint = nextWaypoint++;
    // Piece by piece, as the problem's motion validator certifies (EndpointClearance::motionPieces): the
    // part of a motion inside an approach zone keeps the zone's clearance, the rest the margin.
    const robot::Vector6 delta = q - from;
    double clearance = 0.0;
    for (const collision::MotionPiece& piece : required_.motionPieces(from, q)) {
      const robot::Vector6 pieceStart = from + piece.from * delta;
      const robot::Vector6 pieceEnd = piece.to == 1.0 ? q : robot::Vector6(from + piece.to * delta);
      clearance = piece.clearance;
      if (!certifier || clearance != certifierClearance) {
        certifier.emplace(model_, data_, clearance);
        certifierClearance = clearance;
        if (known) certifier->expect(waypoints.rightCols(waypoints.cols() - (waypoint - 1)));  // from `from` on
        if (!certifier->start(pieceStart)) {
          certifier.reset();
          return false;
        }
      }
      if (!certifier->extend(pieceEnd)) return false;
    }
    // A motion certified for a zone's smaller clearance: its end keeps what a state there must.
    const double state = required_.stateClearanceAt(q);
    return state <= clearance || collision::PathCertifier(model_, data_, state).start(q);
  };
  const JointConversionResult continuation =
      known ? checkConverted(*converted, path, check)
            : convertToJoints(ik_, path, prefix.joints.back(), goal, conversion_, prefix.arcLengths.back(),
                              std::numeric_limits<double>::infinity(), check);
  Walk result;
  result.waypoints = prefix;
  JointConversionResult& combined = result.waypoints;
  combined.joints.insert(combined.joints.end(), continuation.joints.begin() + 1, continuation.joints.end());
  combined.arcLengths.insert(combined.arcLengths.end(), continuation.arcLengths.begin() + 1,
                             continuation.arcLengths.end());
  combined.status = continuation.status;
  combined.reason = continuation.reason;
  combined.failedAtArcLength = continuation.failedAtArcLength;
  combined.refused = continuation.refused;
  if (continuation.refused) result.rejected = RejectedMotion{combined.joints.back(), *continuation.refused};
  return result;
}

std::optional<Walk> PathValidator::screen(const TcpPath& path, const JointConversionResult& prefix,
                                          const std::optional<robot::Vector6>& goal,
                                          JointConversionResult* conversion) {
  if (!certify_) return std::nullopt;  // a waypoint check is as cheap as the screen
  // Each tested waypoint first by withinMargin (one query where the path keeps its distance), then by refuses. The
  // path is converted only up to the waypoint refused: the IK of the rest would be for nothing.
  bool near = false, left = false;  // a tested waypoint came within the margin; a later one was out of it again
  bool stopped = false;
  const auto tested = [&](const robot::Vector6& q) {  // true: q is refused (or the stop request came)
    if (stop_ && stop_()) return stopped = true;      // the walk reports the stop request
    const bool within = withinMargin(q);
    left = left || (near && !within);
    near = near || within;
    return within && refuses(q);
  };
  int waypoint = 0;
  JointConversionResult converted = convertToJoints(ik_, path, prefix.joints.back(), goal, conversion_,
                                                    prefix.arcLengths.back(), std::numeric_limits<double>::infinity(),
                                                    [&](const robot::Vector6&, const robot::Vector6& q, double) {
                                                      return ++waypoint % kScreenStride != 0 || !tested(q);
                                                    });
  // joints[0]: the prefix's last, validated; the refused waypoint (if any) is converted.refused, one past the end.
  const std::vector<robot::Vector6>& joints = converted.joints;
  int refusedAt = 0;
  if (converted.refused) {
    refusedAt = static_cast<int>(joints.size());
  } else {
    const int last = static_cast<int>(joints.size()) - 1;  // tested last, where the stride stepped over it
    if (last % kScreenStride != 0 && tested(joints[last])) refusedAt = last;
  }
  if (stopped) return std::nullopt;
  if (refusedAt == 0 && conversion != nullptr) *conversion = std::move(converted);  // the whole path's, unchecked
  // Where the path came within the margin and left it again before the refusal, the walk may stop there already:
  // it decides then.
  if (refusedAt == 0 || left) return std::nullopt;
  const auto jointsAt = [&](int k) -> const robot::Vector6& {
    return k < static_cast<int>(joints.size()) ? joints[k] : *converted.refused;
  };
  const auto arcLengthAt = [&](int k) {
    return k < static_cast<int>(joints.size()) ? converted.arcLengths[k] : converted.failedAtArcLength;
  };
  // A certified walk breaks off where a pair comes within its acceptance margin of the clearance (motion_check.h):
  // at the first of the waypoints just before the refused one that are all within the margin (the stride may have
  // stepped over them). The search decides by the place of the rejection which leg failed.
  int first = refusedAt;
  while (first > 1 && withinMargin(joints[first - 1])) --first;
  Walk refused;
  refused.waypoints = prefix;
  refused.waypoints.status = ConversionStatus::Rejected;
  refused.waypoints.failedAtArcLength = arcLengthAt(first);
  refused.waypoints.refused = jointsAt(first);
  std::ostringstream reason;
  reason << "the waypoint at TCP arc length " << arcLengthAt(first) << " m of " << path.length()
         << " m is closer than a motion there must keep";
  refused.waypoints.reason = reason.str();
  refused.rejected = RejectedMotion{joints[first - 1], jointsAt(first)};
  return refused;
}

bool PathValidator::refuses(const robot::Vector6& q) {
  const double clearance = required_.motionClearanceAt(q) - kScreenTolerance;
  return clearance > 0.0 && !collision::hasClearance(model_, data_, q, clearance);
}

bool PathValidator::withinMargin(const robot::Vector6& q) {
  return !collision::keepsAcceptanceMargin(model_, data_, q, required_.motionClearanceAt(q));
}

bool PathValidator::keepsMargin(const robot::Vector6& q) {
  // The test of a walk's first waypoint (PathCertifier::start: every pair at least its own m) without the budgets a
  // certifier measures beyond m for the motions that follow: hasClearance's spheres, capsules and hulls settle
  // most pairs before any exact distance, where a certifier's start measures each pair up to m + 5 cm.
  return collision::hasClearance(model_, data_, q, required_.motionClearanceAt(q));
}

Rejection PathValidator::explain(const RejectedMotion& motion) {
  Rejection result;
  result.pairs = collision::collide(model_, data_, motion.to);
  if (!result.pairs.valid) return result;  // contact at the rejected waypoint (the usual case)
  result.collides = false;
  // Closer than the margin at the rejected waypoint: that pair is the reason, one query suffices
  // (the route search asks this for every rejected route).
  // With the per-pair rule a self pair at 1.1 mm is nearer to a refusal than an obstacle pair at 1.1 cm (c = 1 cm),
  // although farther: the pair is the one that keeps least of what the certificate accepts.
  const double clearance = required_.motionClearanceAt(motion.to);
  collision::Shortfall nearest = collision::smallestShortfall(model_, data_, motion.to, clearance);
  result.closest = nearest.distance;
  result.pairs.collisions = {nearest.pair};
  // Closer than its m plus the certificate's acceptance margin: a pair the certificate refuses there.
  if (nearest.shortfall < 0.0) return result;
  // The waypoint keeps that but the motion to it could not be certified: 16 states along it.
  constexpr int kSteps = 16;
  const auto along = [&](int k) -> robot::Vector6 {
    return motion.from + (motion.to - motion.from) * (static_cast<double>(k) / kSteps);
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
    const collision::Shortfall d = collision::smallestShortfall(model_, data_, along(k), clearance);
    if (d.shortfall < nearest.shortfall) {
      nearest = d;
      result.closest = d.distance;
      result.pairs.collisions = {d.pair};
    }
  }
  return result;
}

}  // namespace arcplan::planners
