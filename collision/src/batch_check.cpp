#include "arcplan/collision/batch_check.h"

#include <algorithm>
#include <string>

#include "arcplan/common/error.h"
#include "model_implementation.h"
#include "sphere_prefilter.h"

namespace arcplan::collision {

void areCollisionFree(const CollisionModel& model, CollisionData& data, const Eigen::Ref<const Eigen::MatrixXd>& states,
                      std::vector<bool>& free) {
  if (states.rows() != model.robot().dof()) {
    throw Error("collision query: expected states with " + std::to_string(model.robot().dof()) + " joint values, got " +
                std::to_string(states.rows()));
  }
  const auto& prefilter = detail::implementationOf(model).prefilter;
  detail::Workspace& workspace = detail::workspaceOf(data);
  const Eigen::Index count = states.cols();
  // All true first: a batch the spheres clear (the common case) then writes nothing.
  free.assign(static_cast<std::size_t>(count), true);
  for (Eigen::Index first = 0; first < count; first += detail::prefilter::kLanes) {
    const int lanes = static_cast<int>(std::min<Eigen::Index>(detail::prefilter::kLanes, count - first));
    if (!prefilter || !prefilter->usable()) {
      for (int lane = 0; lane < lanes; ++lane)
        free[first + lane] = detail::exactlyCollisionFree(model, workspace, states.col(first + lane));
      continue;
    }
    prefilter->loadLanes(*workspace.spheres, states.col(first).data(), states.outerStride(), lanes);
    const std::uint32_t cleared = prefilter->freeLanes(*workspace.spheres, lanes);
    if (cleared == (1u << lanes) - 1u) continue;
    // The lanes the spheres do not clear: FCL for the pairs whose spheres touch there.
    detail::collisionGaps(*prefilter, *workspace.spheres);
    for (int lane = 0; lane < lanes; ++lane) {
      if (((cleared >> lane) & 1u) == 0 &&
          detail::unclearedPairsCollide(model, workspace, states.col(first + lane), lane))
        free[first + lane] = false;
    }
  }
}

}  // namespace arcplan::collision
