#include "arcplan/robot/kinematics.h"

#include <cassert>
#include <cmath>

namespace arcplan::robot {

namespace {

// The coordinate axis a joint turns about, as KinematicsData::jointAxes holds it.
signed char coordinateAxis(const Eigen::Vector3d& axis) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(axis[k]) == 1.0 && axis[(k + 1) % 3] == 0.0 && axis[(k + 2) % 3] == 0.0)
      return static_cast<signed char>(axis[k] > 0.0 ? k + 1 : -(k + 1));
  }
  return 0;
}

// The rotation by (c, s) about coordinate axis K of a frame whose other two axes are columns A and B of r, applied to
// r: it mixes those two columns only (fixed indices keep them in registers).
template <int A, int B, class Rotation>
void turnColumns(Rotation&& r, double c, double s) {
  const Eigen::Vector3d first = r.col(A), second = r.col(B);
  r.col(A) = c * first + s * second;
  r.col(B) = c * second - s * first;
}

// Link i's pose from its parent's (already in data) and q.
inline void placeLink(const RobotModel& model, const JointRef& q, std::size_t i, KinematicsData& data) {
  const Link& link = model.links()[i];
  Eigen::Isometry3d& pose = data.linkPoses[i];
  if (link.parent < 0) {
    pose = link.originInParent;
  } else {
    // Eigen's own Isometry product, written out: the compiler kept it a call (8-12 % of a time scaling's CPU).
    const Eigen::Isometry3d& parent = data.linkPoses[link.parent];
    pose.linear().noalias() = parent.linear() * link.originInParent.linear();
    pose.translation().noalias() = parent.linear() * link.originInParent.translation() + parent.translation();
  }
  if (link.joint >= 0) {
    // About a coordinate axis of the link's frame (every UR joint: z in Universal Robots' URDFs, y for three of them
    // in older ones such as MotionBenchMaker's UR5), the rotation mixes the other two columns only: a third of the
    // cost of a general axis-angle product (which took 9 % of an MBM fallback's time).
    const int axis = data.jointAxes[i];
    const double c = std::cos(q[link.joint]), s = (axis < 0 ? -1.0 : 1.0) * std::sin(q[link.joint]);
    switch (axis < 0 ? -axis : axis) {
      case 1:
        turnColumns<1, 2>(pose.linear(), c, s);
        break;
      case 2:
        turnColumns<2, 0>(pose.linear(), c, s);
        break;
      case 3:
        turnColumns<0, 1>(pose.linear(), c, s);
        break;
      default:
        pose.linear() *= Eigen::AngleAxisd(q[link.joint], link.axis).toRotationMatrix();
    }
  }
}

}  // namespace

KinematicsData::KinematicsData(const RobotModel& model)
    : linkPoses(model.links().size(), Eigen::Isometry3d::Identity()) {
  for (const Link& link : model.links()) jointAxes.push_back(link.joint >= 0 ? coordinateAxis(link.axis) : 0);
}

void forwardKinematics(const RobotModel& model, const JointRef& q, KinematicsData& data) {
  assert(q.size() == model.dof());
  for (std::size_t i = 0; i < model.links().size(); ++i) placeLink(model, q, i, data);
}

void chainKinematics(const RobotModel& model, const JointRef& q, int link, KinematicsData& data) {
  assert(q.size() == model.dof());
  if (data.chainLink != link) {
    data.chain.clear();
    for (int l = link; l >= 0; l = model.links()[l].parent) data.chain.push_back(l);
    data.chainLink = link;
  }
  // Links come after their parents (RobotModel): the chain is placed from the base up.
  for (auto l = data.chain.rbegin(); l != data.chain.rend(); ++l)
    placeLink(model, q, static_cast<std::size_t>(*l), data);
}

Eigen::Isometry3d tipPose(const RobotModel& model, const JointRef& q) {
  KinematicsData data(model);
  chainKinematics(model, q, model.tipLink(), data);
  return data.linkPoses[model.tipLink()];
}

void jacobian(const RobotModel& model, const KinematicsData& data, int link, Jacobian& out) {
  if (link < 0) link = model.tipLink();
  out.setZero(6, model.dof());
  const Eigen::Vector3d target = data.linkPoses[link].translation();
  for (int l = link; l >= 0; l = model.links()[l].parent) {
    const Link& current = model.links()[l];
    if (current.joint < 0) continue;
    const Eigen::Vector3d axis = data.linkPoses[l].linear() * current.axis;
    out.block<3, 1>(0, current.joint) = axis.cross(target - data.linkPoses[l].translation());
    out.block<3, 1>(3, current.joint) = axis;
  }
}

Jacobian jacobian(const RobotModel& model, const KinematicsData& data, int link) {
  Jacobian j;
  jacobian(model, data, link, j);
  return j;
}

}  // namespace arcplan::robot
