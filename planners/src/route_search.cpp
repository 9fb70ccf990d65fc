#include "arcplan/planners/route_search.h"

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

}  // namespace arcplan::planners
