#include "arcplan/robot/kinematics.h"

#include <cassert>
#include <cmath>

namespace arcplan::robot {

KinematicsData::KinematicsData(const RobotModel& model)
    : linkPoses(model.links().size(), Eigen::Isometry3d::Identity()) {}

namespace {

// The coordinate axis a joint turns about (0, 1, 2 for x, y, z; sign -1 for a negative one), -1 for any other
// direction.
int coordinateAxis(const Eigen::Vector3d& axis, double& sign) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(axis[k]) == 1.0 && axis[(k + 1) % 3] == 0.0 && axis[(k + 2) % 3] == 0.0) {
      sign = axis[k];
      return k;
    }
  }
  return -1;
}

// Link i's pose from its parent's (already in data) and q.
void placeLink(const RobotModel& model, const JointRef& q, std::size_t i, KinematicsData& data) {
  const Link& link = model.links()[i];
  Eigen::Isometry3d pose = link.parent < 0 ? link.originInParent : data.linkPoses[link.parent] * link.originInParent;
  if (link.joint >= 0) {
    double sign = 1.0;
    const int k = coordinateAxis(link.axis, sign);
    if (k >= 0) {
      // About a coordinate axis of the link's frame (every UR joint: z in Universal Robots' URDFs, y for three of
      // them in older ones such as MotionBenchMaker's UR5), the rotation mixes the other two columns only: a third
      // of the cost of a general axis-angle product (which took 9 % of an MBM fallback's time).
      const double c = std::cos(q[link.joint]), s = sign * std::sin(q[link.joint]);
      const int a = (k + 1) % 3, b = (k + 2) % 3;
      const Eigen::Vector3d first = pose.linear().col(a), second = pose.linear().col(b);
      pose.linear().col(a) = c * first + s * second;
      pose.linear().col(b) = c * second - s * first;
    } else {
      pose.linear() *= Eigen::AngleAxisd(q[link.joint], link.axis).toRotationMatrix();
    }
  }
  data.linkPoses[i] = pose;
}

}  // namespace

void forwardKinematics(const RobotModel& model, const JointRef& q, KinematicsData& data) {
  assert(q.size() == model.dof());
  for (std::size_t i = 0; i < model.links().size(); ++i) placeLink(model, q, i, data);
}

void chainKinematics(const RobotModel& model, const JointRef& q, int link, KinematicsData& data) {
  assert(q.size() == model.dof());
  // Links come after their parents (RobotModel): the chain is placed from the base up.
  std::vector<int>& chain = data.chain;
  chain.clear();
  for (int l = link; l >= 0; l = model.links()[l].parent) chain.push_back(l);
  for (auto l = chain.rbegin(); l != chain.rend(); ++l) placeLink(model, q, static_cast<std::size_t>(*l), data);
}

Eigen::Isometry3d tipPose(const RobotModel& model, const JointRef& q) {
  KinematicsData data(model);
  chainKinematics(model, q, model.tipLink(), data);
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
