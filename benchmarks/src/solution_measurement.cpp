#include "arcplan/benchmarks/solution_measurement.h"

#include <algorithm>

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
  const trajectory::ClearanceFunction clearance = [&](const robot::Vector6& q) {
    const collision::DistanceReport measured = collision::distance(model, data, q);
    solution.clearanceMargin =
        std::min(solution.clearanceMargin, collision::clearanceOf(measured) - rule.stateClearanceAt(q));
    return measured.obstacleDistance;
  };
  solution.measurement = trajectory::measurePath(model.robot(), path, scaling, clearance);
  return solution;
}

}  // namespace arcplan::benchmarks
