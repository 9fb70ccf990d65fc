#pragma once
// What arcplan.Robot holds: the immutable model, shared with the scenes and results made from it,
// and its inverse kinematics, built on first use (it throws for a chain that is no UR arm).
#include <memory>

#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::python {

struct RobotHandle {
  explicit RobotHandle(std::shared_ptr<const robot::RobotModel> robotModel) : model(std::move(robotModel)) {}
  const robot::UrInverseKinematics& ik() const;

  std::shared_ptr<const robot::RobotModel> model;
  mutable std::shared_ptr<const robot::UrInverseKinematics> inverseKinematics;  // guarded by the GIL
};

}  // namespace arcplan::python
