#include "route_search.h"

#include <algorithm>

namespace arcplan::planners {
namespace {

double polylineLength(const std::vector<Eigen::Vector3d>& points) {
  double length = 0.0;
  for (std::size_t k = 0; k + 1 < points.size(); ++k) length += (points[k + 1] - points[k]).norm();
  return length;
}

}  // namespace

RouteSearch::RouteSearch(const Eigen::Vector3d& start, const Eigen::Vector3d& goal, std::size_t maxViaPoints)
    : maxViaPoints_(maxViaPoints) {
  push(Route{{start, goal}, {}, 0.0});
}

RouteSearch::Leg RouteSearch::legOf(const Route& route, std::size_t k) {
  const Eigen::Vector3d& a = route.points[k];
  const Eigen::Vector3d& b = route.points[k + 1];
  return {{a.x(), a.y(), a.z()}, {b.x(), b.y(), b.z()}};
}

void RouteSearch::push(Route route) {
  route.length = polylineLength(route.points);
  queue_.push(std::move(route));
  ++queued_;
}

std::optional<Route> RouteSearch::next() {
  while (!queue_.empty()) {
    Route route = queue_.top();
    queue_.pop();
    bool knownToFail = false;
    for (std::size_t k = 0; k + 1 < route.points.size() && !knownToFail; ++k) {
      knownToFail = failedLegs_.count(legOf(route, k)) > 0;
    }
    if (knownToFail) continue;
    ++tried_;
    return route;
  }
  return std::nullopt;
}

void RouteSearch::removeLeg(const Route& route, std::size_t leg) { failedLegs_.insert(legOf(route, leg)); }

void RouteSearch::legFailed(const Route& route, std::size_t leg, const std::vector<ViaCandidate>& ways) {
  removeLeg(route, leg);
  for (const ViaCandidate& way : ways) {
    if (route.points.size() - 2 + way.points.size() > maxViaPoints_) continue;
    Route detour;
    // Sized once: a failed leg queues up to 120 detours, and growing their vectors took ~7 % of dropping a leg.
    detour.points.reserve(route.points.size() + way.points.size());
    detour.margins.reserve(route.margins.size() + way.points.size());
    detour.points.assign(route.points.begin(), route.points.begin() + static_cast<std::ptrdiff_t>(leg) + 1);
    detour.margins.assign(route.margins.begin(), route.margins.begin() + static_cast<std::ptrdiff_t>(leg));
    for (const Eigen::Vector3d& point : way.points) {
      detour.points.push_back(point);
      detour.margins.push_back(way.margin);
    }
    detour.points.insert(detour.points.end(), route.points.begin() + static_cast<std::ptrdiff_t>(leg) + 1,
                         route.points.end());
    detour.margins.insert(detour.margins.end(), route.margins.begin() + static_cast<std::ptrdiff_t>(leg),
                          route.margins.end());
    push(std::move(detour));
  }
}

Eigen::Vector3d towardChord(const Eigen::Vector3d& prev, const Eigen::Vector3d& via, const Eigen::Vector3d& next,
                            double distance) {
  const Eigen::Vector3d chord = next - prev;
  const double along =
      chord.squaredNorm() > 0.0 ? std::clamp((via - prev).dot(chord) / chord.squaredNorm(), 0.0, 1.0) : 0.0;
  const Eigen::Vector3d toChord = prev + along * chord - via;
  const double gap = toChord.norm();
  return via + (gap <= distance ? 1.0 : distance / gap) * toChord;
}

RouteShortening::RouteShortening(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal, BlendedPath validated,
                                 std::vector<double> margins, int maxTrials)
    : start_(start),
      goal_(goal),
      validated_(validated),
      best_(std::move(validated)),
      margins_(std::move(margins)),
      trialsLeft_(maxTrials),
      done_(validated_.points().size() == 2) {}

std::optional<BlendedPath> RouteShortening::candidateAt(double fraction) const {
  // Below this a leg leaves no room for a blend (m). A trial must gain at least kLeastGain (m, 40 ms of
  // execution at 0.25 m/s): the walk of a trial that validates grazes the bodies at the clearance and costs
  // 2-8x the rest of a simple search, and a smaller fraction of the margin gains less, so the bisection
  // stops paying walks there.
  constexpr double kShortestLeg = 0.008, kLeastGain = 0.01;
  const std::vector<Eigen::Vector3d>& original = validated_.points();
  const std::size_t viaCount = original.size() - 2;
  std::vector<Eigen::Vector3d> points = original;
  for (std::size_t i = 1; i <= viaCount; ++i) {
    points[i] = towardChord(points[i - 1], original[i], original[i + 1], fraction * margins_.at(i - 1));
    if ((points[i] - points[i - 1]).norm() < kShortestLeg) return std::nullopt;
  }
  if ((points[viaCount + 1] - points[viaCount]).norm() < kShortestLeg) return std::nullopt;
  std::vector<double> blends = validated_.blends();
  for (std::size_t j = 0; j < viaCount; ++j) blends[j] = std::min(blends[j], BlendedPath::maxBlend(points, j));
  BlendedPath candidate(start_, goal_, std::vector<Eigen::Vector3d>(points.begin() + 1, points.end() - 1), blends);
  if (candidate.length() > best_.length() - kLeastGain) return std::nullopt;
  return candidate;
}

std::optional<BlendedPath> RouteShortening::next() {
  // Every via point moves the same fraction of its margin: the whole margin first (each via point as
  // close as the clearance alone would put it), then bisected between what was kept and what was not.
  while (!done_ && trialsLeft_ > 0) {
    --trialsLeft_;
    pending_ = std::min(1.0, 0.5 * (kept_ + refused_));
    candidate_ = candidateAt(pending_);
    if (candidate_) return candidate_;
    refused_ = pending_;
  }
  return std::nullopt;
}

void RouteShortening::accept(bool valid) {
  if (!candidate_) return;
  if (valid) {
    best_ = *candidate_;
    done_ = pending_ >= 1.0;
    kept_ = pending_;
  } else {
    refused_ = pending_;
  }
  candidate_.reset();
}

}  // namespace arcplan::planners
