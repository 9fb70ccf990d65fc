#pragma once
// Postures tested one at a time: the configuration the IK gives for a TCP pose on the start's branch (what
// a walk would reach there), held against the planner's margin. Internal to the arc planner's auto mode
// (via_point_planning.cpp): its cheap tests of via points, probes and detours before a certified walk.
#include <Eigen/Geometry>
#include <optional>

#include "arc_planning.h"
#include "arcplan/collision/collision_model.h"

namespace arcplan::planners::detail {

// The configuration at a TCP pose on the start's branch (what a walk would reach there).
inline std::optional<robot::Vector6> postureAt(const ArcQuery& query, const Eigen::Isometry3d& pose) {
  return query.ik.solveBranch(pose, query.startBranch, query.start[5]);
}

// One posture tested on its own against the margin: what the search asks of via points, probes and
// detours before any certified walk.
class PostureTest {
public:
  explicit PostureTest(const ArcQuery& query) : query_(query), data_(query.model) {}

  // The margin as a walk's first waypoint tests it (PathValidator::keepsMargin: a posture in an approach
  // zone is held to the zone's clearance, as a walk holds it); with `slack` (m) more, by the
  // cheapest bounds that decide it (collision::hasClearance: spheres, capsules, hulls before exact
  // distances), the test of the many detour probes.
  bool keepsMargin(const robot::Vector6& q, double slack = 0.0) {
    if (slack <= 0.0) return query_.validator.keepsMargin(q);
    return collision::hasClearance(query_.model, data_, q, query_.validator.margin() + slack);
  }
  // The posture at a TCP pose on the start's branch keeps the margin (false where the branch has none).
  bool clearAt(const Eigen::Isometry3d& pose, double slack = 0.0) {
    const auto q = postureAt(query_, pose);
    return q && keepsMargin(*q, slack);
  }

private:
  const ArcQuery& query_;
  collision::CollisionData data_;
};

}  // namespace arcplan::planners::detail
