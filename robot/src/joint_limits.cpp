#include "arcplan/robot/joint_limits.h"

#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"

namespace arcplan::robot {

std::optional<int> firstJointOutsideLimits(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                                           double tolerance) {
  if (q.size() != model.dof()) {
    throw Error("robot " + model.name() + " has " + std::to_string(model.dof()) + " joints, but the joint vector has " +
                std::to_string(q.size()) + " values");
  }
  for (int j = 0; j < model.dof(); ++j) {
    const JointLimits& limits = model.joints()[j].limits;
    // Written as "within" so that NaN, for which every comparison is false, is outside.
    const bool within = q[j] >= limits.lower - tolerance && q[j] <= limits.upper + tolerance;
    if (!within) return j;
  }
  return std::nullopt;
}

std::string outsideLimitsText(const RobotModel& model, int joint, double value, const std::string& jointLabel) {
  const Joint& described = model.joints().at(static_cast<std::size_t>(joint));
  return jointLabel + " (" + described.name + ") = " + formatNumber(value, 9) + " rad is outside its limits [" +
         formatNumber(described.limits.lower, 9) + ", " + formatNumber(described.limits.upper, 9) + "]";
}

}  // namespace arcplan::robot
