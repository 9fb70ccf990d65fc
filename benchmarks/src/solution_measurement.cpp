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
  collision::PathClearance required(validity->requiredClearance(), path);
  MeasuredSolution solution;
  const trajectory::ClearanceFunction clearance = [&](const robot::Vector6& q) {
    const double measured = collision::distance(model, data, q).obstacleDistance;
    solution.clearanceMargin = std::min(solution.clearanceMargin, measured - required.next(q));
    return measured;
  };
  solution.measurement = trajectory::measurePath(model.robot(), path, scaling, clearance);
  return solution;
}

}  // namespace arcplan::benchmarks
