#include "arcplan/benchmarks/solution_measurement.h"

#include <algorithm>
#include <cmath>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/endpoint_clearance.h"
#include "arcplan/collision/ompl_validity.h"
#include "arcplan/common/error.h"

namespace arcplan::benchmarks {

MeasuredSolution measureSolution(const planners::PlanningProblem& problem, const trajectory::JointPath& path,
                                 const std::optional<trajectory::TimeScalingOptions>& scaling) {
  const auto* validity =
      dynamic_cast<const collision::CollisionStateValidityChecker*>(problem.setup->getStateValidityChecker().get());
  if (validity == nullptr) throw Error("measuring a solution: the problem has no arcplan validity checker");
  const collision::CollisionModel& model = *problem.collisionModel;
  collision::CollisionData data(model);
  const collision::EndpointClearance& rule = validity->requiredClearance();
  MeasuredSolution solution;
  // Judged as the validity checker judges a state: what stateClearanceAt(q) asks, kept as the one rule says
  // (clearanceOf: from obstacles, and between the robot's own bodies up to kSelfClearance); the metric handed
  // back stays the obstacle distance (min_clearance_m).
  const trajectory::ClearanceFunction clearance = [&](const robot::Vector6& q, double enough) {
    // A waypoint whose obstacles are at least `atLeast` away and its own bodies min(atLeast, kSelfClearance)
    // (hasClearance's rule, which bounds clearanceOf by atLeast too) lowers neither the smallest obstacle distance
    // so far nor the margin: its distance is not measured (dense paths have thousands of waypoints, a few near their
    // closest point, and a full distance query measured every one).
    const double required = rule.stateClearanceAt(q);
    const double atLeast = std::max(enough, solution.clearanceMargin + required);
    if (std::isfinite(atLeast) && atLeast > 0.0 && collision::hasClearance(model, data, q, atLeast)) return atLeast;
    const collision::DistanceReport measured = collision::distance(model, data, q);
    solution.clearanceMargin = std::min(solution.clearanceMargin, collision::clearanceOf(measured) - required);
    return measured.obstacleDistance;
  };
  solution.measurement = trajectory::measurePath(model.robot(), path, scaling, clearance);
  return solution;
}

}  // namespace arcplan::benchmarks
