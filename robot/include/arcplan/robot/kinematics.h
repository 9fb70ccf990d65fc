#pragma once
// Forward kinematics and the geometric Jacobian of a RobotModel's chain.
#include <vector>

#include <Eigen/Geometry>

#include "arcplan/robot/robot_model.h"

namespace arcplan::robot {

using JointVector = Eigen::VectorXd;
using JointRef = Eigen::Ref<const Eigen::VectorXd>;
using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;  // rows: linear (3), angular (3)

// Scratch space for the kinematics of one model; one per thread, reused across calls.
struct KinematicsData {
  explicit KinematicsData(const RobotModel& model);
  std::vector<Eigen::Isometry3d> linkPoses;  // in the base link frame, indexed like model.links()
  // Per link, the coordinate axis its joint turns about (1, 2, 3 for x, y, z, negative for -x, -y, -z; 0 for any other
  // axis or no joint), worked out once from the model.
  std::vector<signed char> jointAxes;
  // chainKinematics: the chain of link chainLink, from it down to the base.
  std::vector<int> chain;
  int chainLink = -1;
};

// Poses of every link of the model for joint vector q (size model.dof()).
void forwardKinematics(const RobotModel& model, const JointRef& q, KinematicsData& data);

// Poses of `link` and of its ancestors only (the other links' poses left as they were): all that the link's pose and
// jacobian(model, data, link) need, without the links beside the chain (a gripper's fingers, sensors: 12 of the 22
// links of MotionBenchMaker's UR5).
void chainKinematics(const RobotModel& model, const JointRef& q, int link, KinematicsData& data);

// Pose of the tip link (allocates a workspace; use chainKinematics in loops).
Eigen::Isometry3d tipPose(const RobotModel& model, const JointRef& q);

// Geometric Jacobian of `link` (default: tip) in the base frame, reference point at the link
// origin: [v; w] = J(q)·qd. Uses the poses of `link` and its ancestors in data.linkPoses, so call forwardKinematics(q)
// or chainKinematics(q, link) first.
Jacobian jacobian(const RobotModel& model, const KinematicsData& data, int link = -1);
// The same into `out` (resized; no allocation once it has the size): for loops.
void jacobian(const RobotModel& model, const KinematicsData& data, int link, Jacobian& out);

}  // namespace arcplan::robot
