#include "route_search.h"

#include <algorithm>

namespace arcplan::planners {
namespace {

// The length of the polyline route.points[0..leg], way, route.points[leg + 1..]: summed in that order, as over the
// built route's points, so that equal routes get equal lengths to the bit (the queue's order depends on them).
double detourLength(const Route& route, std::size_t leg, const ViaCandidate& way) {
  double length = 0.0;
  const Eigen::Vector3d* previous = &route.points.front();
  const auto add = [&](const Eigen::Vector3d& point) {
    length += (point - *previous).norm();
    previous = &point;
  };
  for (std::size_t k = 1; k <= leg; ++k) add(route.points[k]);
  for (const Eigen::Vector3d& point : way.points) add(point);
  for (std::size_t k = leg + 1; k < route.points.size(); ++k) add(route.points[k]);
  return length;
}

}  // namespace

RouteSearch::RouteSearch(const Eigen::Vector3d& start, const Eigen::Vector3d& goal, std::size_t maxViaPoints)
    : maxViaPoints_(maxViaPoints) {
  auto straight = std::make_shared<Route>(Route{{start, goal}, {}, 0.0});
  straight->length = detourLength(*straight, 0, ViaCandidate{});
  push(Queued{straight->length, straight, nullptr});
}

RouteSearch::Leg RouteSearch::legOf(const Route& route, std::size_t k) {
  const Eigen::Vector3d& a = route.points[k];
  const Eigen::Vector3d& b = route.points[k + 1];
  return {{a.x(), a.y(), a.z()}, {b.x(), b.y(), b.z()}};
}

Route RouteSearch::build(const Queued& queued) {
  if (!queued.ways) return *queued.from;
  const Route& from = *queued.from;
  const ViaCandidate& way = (*queued.ways)[queued.way];
  const auto leg = static_cast<std::ptrdiff_t>(queued.leg);
  Route detour;
  detour.points.reserve(from.points.size() + way.points.size());
  detour.margins.reserve(from.margins.size() + way.points.size());
  detour.points.assign(from.points.begin(), from.points.begin() + leg + 1);
  detour.margins.assign(from.margins.begin(), from.margins.begin() + leg);
  for (const Eigen::Vector3d& point : way.points) {
    detour.points.push_back(point);
    detour.margins.push_back(way.margin);
  }
  detour.points.insert(detour.points.end(), from.points.begin() + leg + 1, from.points.end());
  detour.margins.insert(detour.margins.end(), from.margins.begin() + leg, from.margins.end());
  detour.length = queued.length;
  return detour;
}

void RouteSearch::push(Queued queued) {
  queue_.push(std::move(queued));
  ++queued_;
}

std::optional<Route> RouteSearch::next() {
  while (!queue_.empty()) {
    Route route = build(queue_.top());
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

void RouteSearch::legFailed(const Route& route, std::size_t leg, std::vector<ViaCandidate> ways) {
  removeLeg(route, leg);
  const auto from = std::make_shared<const Route>(route);
  const auto shared = std::make_shared<const std::vector<ViaCandidate>>(std::move(ways));
  for (std::size_t w = 0; w < shared->size(); ++w) {
    const ViaCandidate& way = (*shared)[w];
    if (route.points.size() - 2 + way.points.size() > maxViaPoints_) continue;
    push(Queued{detourLength(route, leg, way), from, shared, leg, w});
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
