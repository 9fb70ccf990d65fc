#pragma once
// The joint-limit rule: whether a joint vector lies within a robot's limits, and how a value outside
// them is reported. Every input that gives joint values (`robot fk --joints`, a joint path CSV, a
// query's joints) applies this one rule, so they accept and refuse the same vectors.
#include <optional>
#include <string>

#include <Eigen/Core>

#include "arcplan/robot/robot_model.h"

namespace arcplan::robot {

// The first joint j whose q[j] is below lower - tolerance or above upper + tolerance (NaN is outside
// any limits), or nullopt when every joint is within. `tolerance` [rad] >= 0 admits values computed
// at a limit that differ from it in the last bits (IK at ±2π). Throws arcplan::Error when q does not
// have one value per joint of `model`.
std::optional<int> firstJointOutsideLimits(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                                           double tolerance = 0.0);

// "<jointLabel> (<joint name>) = <value> rad is outside its limits [<lower>, <upper>]", numbers with 9
// significant digits. `jointLabel` names joint `joint` as the caller's input does ("joint 2", "q2").
std::string outsideLimitsText(const RobotModel& model, int joint, double value, const std::string& jointLabel);

}  // namespace arcplan::robot
