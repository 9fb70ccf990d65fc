#pragma once
// The lazy search of the via-point graph: routes start -> via points -> goal, shortest first.
// Internal to the arc planner (via_point_planning.cpp).
//
// The graph's vertices are the start, the goal and the via-point candidates of the obstacle
// clusters found so far (via_points.h); its edges are straight legs. Edges are evaluated lazily, as
// in LazyPRM: only the legs of the currently shortest route are checked (by walking it, which the
// caller does), a leg that fails is removed from the graph, and the cluster that blocked it adds its
// candidates as new ways round that leg. A route's cost is its polyline length: at the TCP speed
// limit, execution time is length / v_max plus the fixed ramps, so the shortest route is the fastest.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <queue>
#include <set>
#include <utility>
#include <vector>

#include "arcplan/planners/blended_path.h"
#include "via_points.h"

namespace arcplan::planners {

struct Route {
  std::vector<Eigen::Vector3d> points;  // start, via points, goal
  std::vector<double> margins;          // per via point: the margin its candidate keeps (m)
  double length = 0.0;                  // polyline length (m)
};

class RouteSearch {
public:
  // Starts with the straight route start -> goal. `maxViaPoints` bounds a route's via points.
  RouteSearch(const Eigen::Vector3d& start, const Eigen::Vector3d& goal, std::size_t maxViaPoints);

  // The shortest route none of whose legs is known to fail; nothing once every route is exhausted.
  std::optional<Route> next();
  // Leg k of `route` failed: remove it, and add `route` with that leg replaced by each candidate.
  void legFailed(const Route& route, std::size_t leg, std::vector<ViaCandidate> ways);
  // Leg k of `route` failed for a reason no via point removes (e.g. unreachable): remove it only.
  void removeLeg(const Route& route, std::size_t leg);

  std::size_t routesTried() const { return tried_; }
  std::size_t routesQueued() const { return queued_; }

private:
  using Point = std::array<double, 3>;
  using Leg = std::pair<Point, Point>;
  static Leg legOf(const Route& route, std::size_t k);
  // A queued route, built only when taken: `from` with its leg `leg` replaced by way `way` of `ways` (`from` itself
  // when `ways` is null). A failed leg queues up to 120 of them and most are never taken: building each route's
  // vectors at once was most of what dropping a leg cost.
  struct Queued {
    double length;
    std::shared_ptr<const Route> from;
    std::shared_ptr<const std::vector<ViaCandidate>> ways;
    std::size_t leg = 0, way = 0;
  };
  static Route build(const Queued& queued);
  void push(Queued queued);

  struct Longer {
    bool operator()(const Queued& a, const Queued& b) const { return a.length > b.length; }
  };
  std::priority_queue<Queued, std::vector<Queued>, Longer> queue_;
  std::set<Leg> failedLegs_;
  std::size_t maxViaPoints_;
  std::size_t tried_ = 0, queued_ = 0;
};

// `via` moved up to `distance` toward the nearest point of the segment prev–next (never past it). The
// polyline prev → via → next gets no longer: the sum of distances to prev and next is convex and least
// on their segment, so it does not grow along the way there.
Eigen::Vector3d towardChord(const Eigen::Vector3d& prev, const Eigen::Vector3d& via, const Eigen::Vector3d& next,
                            double distance);

// A route that validated, made shorter where it still validates: the search's margins come in steps,
// so every via point is moved toward the chord of its neighbours by the same fraction of its margin —
// the whole margin first (the clearance-only position), then bisected — blends kept where they still
// fit. A candidate is offered only if it is shorter than the best so far; the caller validates it
// and gives the verdict, at most `maxTrials` trials. best() is the shortest path accepted (the
// validated one if none). `validated` runs from `start` to `goal` (the poses it was built with).
class RouteShortening {
public:
  RouteShortening(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal, BlendedPath validated,
                  std::vector<double> margins, int maxTrials);

  // The next candidate to validate; nothing once the trials are spent or the whole margin was kept.
  // Each candidate needs its verdict (accept) before the next call.
  std::optional<BlendedPath> next();
  // The verdict on the candidate next() returned last.
  void accept(bool valid);
  const BlendedPath& best() const { return best_; }

private:
  std::optional<BlendedPath> candidateAt(double fraction) const;

  Eigen::Isometry3d start_, goal_;
  BlendedPath validated_, best_;
  std::vector<double> margins_;
  int trialsLeft_;
  double kept_ = 0.0, refused_ = 2.0;  // fractions of the margins kept and refused so far
  double pending_ = 0.0;               // the fraction of the candidate awaiting its verdict
  std::optional<BlendedPath> candidate_;
  bool done_ = false;
};

}  // namespace arcplan::planners
