#pragma once
// Rigid-body dynamics of a RobotModel's chain from its URDF inertials: recursive Newton–Euler
// inverse dynamics, the mass matrix and gravity torques built from it, and the regressor of an
// unknown point-mass payload at the tip (linear in its mass and first moment).
//
// Conventions: torques are the joint torques the drives must produce, τ = M(q)·qdd + C(q,qd)·qd + g(q)
// (+ payload); gravity is given in the base link frame; the payload sits in the tip link's frame.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/robot_model.h"

namespace arcplan::robot {

// A point mass rigidly attached to the tip link (a tool or a carried part).
struct Payload {
  double mass = 0.0;                                       // kg
  Eigen::Vector3d centerOfMass = Eigen::Vector3d::Zero();  // m, in the tip link frame
};

struct DynamicsParameters {
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};  // m/s², in the base link frame
  Payload payload;
};

// Scratch space of the Newton–Euler passes; one per thread, reused across calls.
struct DynamicsData {
  explicit DynamicsData(const RobotModel& model);
  std::vector<Eigen::Matrix3d> rotationToParent;  // child axes expressed in the parent frame
  std::vector<Eigen::Vector3d> angularVelocity;   // in the link frame
  std::vector<Eigen::Vector3d> angularAcceleration;
  std::vector<Eigen::Vector3d> linearAcceleration;  // of the link origin, gravity folded in (a - g)
  std::vector<Eigen::Vector3d> force;               // wrench the parent exerts on the link, link frame
  std::vector<Eigen::Vector3d> moment;              // about the link origin
};

// τ(q, qd, qdd) by recursive Newton–Euler over every link of the model (a tree ordered parents
// first). Vectors have model.dof() entries.
Eigen::VectorXd inverseDynamics(const RobotModel& model, const JointRef& q, const JointRef& qd, const JointRef& qdd,
                                DynamicsData& data, const DynamicsParameters& parameters = {});

// g(q): the torques that hold the arm still against gravity.
Eigen::VectorXd gravityTorque(const RobotModel& model, const JointRef& q, DynamicsData& data,
                              const DynamicsParameters& parameters = {});

// M(q), column k = inverse dynamics with qdd = e_k, qd = 0 and no gravity.
Eigen::MatrixXd massMatrix(const RobotModel& model, const JointRef& q, DynamicsData& data,
                           const DynamicsParameters& parameters = {});

// Y(q, qd, qdd) with τ_payload = Y·[m, m·cx, m·cy, m·cz] for a payload of mass m at centre c in the
// tip frame. The payload's own rotational inertia about its centre is zero (a point mass) and its
// second moment m·c·cᵀ about the tip origin is neglected: for a tool a few cm from the flange it
// adds less than m·|c|²·|qdd| (≈ 0.02 N·m for 2 kg at 0.1 m and 1 rad/s²).
Eigen::Matrix<double, Eigen::Dynamic, 4> payloadRegressor(const RobotModel& model, const JointRef& q,
                                                          const JointRef& qd, const JointRef& qdd, DynamicsData& data,
                                                          const Eigen::Vector3d& gravity = {0.0, 0.0, -9.81});

}  // namespace arcplan::robot
