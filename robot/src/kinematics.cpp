#include "arcplan/robot/kinematics.h"

#include <cassert>
#include <cmath>

namespace arcplan::robot {

KinematicsData::KinematicsData(const RobotModel& model)
    : linkPoses(model.links().size(), Eigen::Isometry3d::Identity()) {}

void forwardKinematics(const RobotModel& model, const JointRef& q, KinematicsData& data) {
  assert(q.size() == model.dof());
  const auto& links = model.links();
  for (std::size_t i = 0; i < links.size(); ++i) {
    const Link& link = links[i];
    Eigen::Isometry3d pose = link.parent < 0 ? link.originInParent : data.linkPoses[link.parent] * link.originInParent;
    if (link.joint >= 0) {
      if (link.axis == Eigen::Vector3d::UnitZ()) {
        // The usual URDF convention (every UR joint): rotating about the local z axis only mixes
        // the first two columns, a third of the cost of a general axis-angle product.
        const double c = std::cos(q[link.joint]), s = std::sin(q[link.joint]);
        const Eigen::Vector3d x = pose.linear().col(0), y = pose.linear().col(1);
        pose.linear().col(0) = c * x + s * y;
        pose.linear().col(1) = c * y - s * x;
      } else {
        pose.linear() *= Eigen::AngleAxisd(q[link.joint], link.axis).toRotationMatrix();
      }
    }
    data.linkPoses[i] = pose;
  }
}

Eigen::Isometry3d tipPose(const RobotModel& model, const JointRef& q) {
  KinematicsData data(model);
  forwardKinematics(model, q, data);
  return data.linkPoses[model.tipLink()];
}

Jacobian jacobian(const RobotModel& model, const KinematicsData& data, int link) {
  if (link < 0) link = model.tipLink();
  Jacobian j = Jacobian::Zero(6, model.dof());
  const Eigen::Vector3d target = data.linkPoses[link].translation();
  for (int l = link; l >= 0; l = model.links()[l].parent) {
    const Link& current = model.links()[l];
    if (current.joint < 0) continue;
    const Eigen::Vector3d axis = data.linkPoses[l].linear() * current.axis;
    j.block<3, 1>(0, current.joint) = axis.cross(target - data.linkPoses[l].translation());
    j.block<3, 1>(3, current.joint) = axis;
  }
  return j;
}

}  // namespace arcplan::robot
