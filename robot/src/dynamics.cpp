#include "arcplan/robot/dynamics.h"

#include <cassert>

namespace arcplan::robot {
namespace {

// Outward pass: velocities and accelerations of every link in its own frame. The base accelerates
// upwards at -g, which adds the weight of every link without a separate gravity term.
void propagateMotion(const RobotModel& model, const JointRef& q, const JointRef& qd, const JointRef& qdd,
                     const Eigen::Vector3d& gravity, DynamicsData& data) {
  const auto& links = model.links();
  for (std::size_t i = 0; i < links.size(); ++i) {
    const Link& link = links[i];
    Eigen::Matrix3d rotation = link.originInParent.linear();
    if (link.joint >= 0) rotation *= Eigen::AngleAxisd(q[link.joint], link.axis).toRotationMatrix();
    data.rotationToParent[i] = rotation;
    // The chain base is the frame gravity is given in.
    Eigen::Vector3d omega = Eigen::Vector3d::Zero(), alpha = Eigen::Vector3d::Zero(), accel = -gravity;
    if (link.parent >= 0) {
      const Eigen::Matrix3d toChild = rotation.transpose();
      const Eigen::Vector3d& parentOmega = data.angularVelocity[link.parent];
      const Eigen::Vector3d& parentAlpha = data.angularAcceleration[link.parent];
      const Eigen::Vector3d offset = link.originInParent.translation();
      accel = toChild * (data.linearAcceleration[link.parent] + parentAlpha.cross(offset) +
                         parentOmega.cross(parentOmega.cross(offset)));
      omega = toChild * parentOmega;
      alpha = toChild * parentAlpha;
    }
    if (link.joint >= 0) {
      const Eigen::Vector3d jointRate = link.axis * qd[link.joint];
      alpha += omega.cross(jointRate) + link.axis * qdd[link.joint];
      omega += jointRate;
    }
    data.angularVelocity[i] = omega;
    data.angularAcceleration[i] = alpha;
    data.linearAcceleration[i] = accel;
  }
}

// Inward pass from the given per-link wrenches (already stored in data.force/moment): adds each
// link's wrench to its parent and reads the joint torques off the joint axes.
void accumulateWrenches(const RobotModel& model, DynamicsData& data, Eigen::Ref<Eigen::VectorXd> tau) {
  const auto& links = model.links();
  for (std::size_t i = links.size(); i-- > 0;) {
    const Link& link = links[i];
    if (link.joint >= 0) tau[link.joint] = link.axis.dot(data.moment[i]);
    if (link.parent < 0) continue;
    const Eigen::Vector3d forceInParent = data.rotationToParent[i] * data.force[i];
    data.force[link.parent] += forceInParent;
    data.moment[link.parent] +=
        data.rotationToParent[i] * data.moment[i] + link.originInParent.translation().cross(forceInParent);
  }
}

}  // namespace

DynamicsData::DynamicsData(const RobotModel& model)
    : rotationToParent(model.links().size(), Eigen::Matrix3d::Identity()),
      angularVelocity(model.links().size(), Eigen::Vector3d::Zero()),
      angularAcceleration(model.links().size(), Eigen::Vector3d::Zero()),
      linearAcceleration(model.links().size(), Eigen::Vector3d::Zero()),
      force(model.links().size(), Eigen::Vector3d::Zero()),
      moment(model.links().size(), Eigen::Vector3d::Zero()) {}

Eigen::VectorXd inverseDynamics(const RobotModel& model, const JointRef& q, const JointRef& qd, const JointRef& qdd,
                                DynamicsData& data, const DynamicsParameters& parameters) {
  assert(q.size() == model.dof() && qd.size() == model.dof() && qdd.size() == model.dof());
  propagateMotion(model, q, qd, qdd, parameters.gravity, data);
  const auto& links = model.links();
  for (std::size_t i = 0; i < links.size(); ++i) {
    const Eigen::Vector3d& omega = data.angularVelocity[i];
    const Eigen::Vector3d& alpha = data.angularAcceleration[i];
    const Eigen::Vector3d& accel = data.linearAcceleration[i];
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
    auto addBody = [&](double mass, const Eigen::Vector3d& com, const Eigen::Matrix3d& inertiaAboutCom) {
      const Eigen::Vector3d comForce = mass * (accel + alpha.cross(com) + omega.cross(omega.cross(com)));
      force += comForce;
      moment += inertiaAboutCom * alpha + omega.cross(inertiaAboutCom * omega) + com.cross(comForce);
    };
    if (links[i].hasInertial) {
      addBody(links[i].inertial.mass, links[i].inertial.centerOfMass, links[i].inertial.inertiaAboutCom);
    }
    if (static_cast<int>(i) == model.tipLink() && parameters.payload.mass != 0.0) {
      addBody(parameters.payload.mass, parameters.payload.centerOfMass, Eigen::Matrix3d::Zero());
    }
    data.force[i] = force;
    data.moment[i] = moment;
  }
  Eigen::VectorXd tau(model.dof());
  accumulateWrenches(model, data, tau);
  return tau;
}

Eigen::VectorXd gravityTorque(const RobotModel& model, const JointRef& q, DynamicsData& data,
                              const DynamicsParameters& parameters) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.dof());
  return inverseDynamics(model, q, zero, zero, data, parameters);
}

Eigen::MatrixXd massMatrix(const RobotModel& model, const JointRef& q, DynamicsData& data,
                           const DynamicsParameters& parameters) {
  DynamicsParameters withoutGravity = parameters;
  withoutGravity.gravity.setZero();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.dof());
  Eigen::MatrixXd mass(model.dof(), model.dof());
  for (int k = 0; k < model.dof(); ++k) {
    mass.col(k) = inverseDynamics(model, q, zero, Eigen::VectorXd::Unit(model.dof(), k), data, withoutGravity);
  }
  return mass;
}

Eigen::Matrix<double, Eigen::Dynamic, 4> payloadRegressor(const RobotModel& model, const JointRef& q,
                                                          const JointRef& qd, const JointRef& qdd, DynamicsData& data,
                                                          const Eigen::Vector3d& gravity) {
  propagateMotion(model, q, qd, qdd, gravity, data);
  const int tip = model.tipLink();
  const Eigen::Vector3d& omega = data.angularVelocity[tip];
  const Eigen::Vector3d& alpha = data.angularAcceleration[tip];
  const Eigen::Vector3d& accel = data.linearAcceleration[tip];
  // Wrench on the tip (link frame, about its origin) per unit parameter: mass, then first moment.
  Eigen::Matrix<double, 3, 4> force, moment;
  force.col(0) = accel;
  moment.col(0).setZero();
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d unit = Eigen::Vector3d::Unit(axis);
    force.col(axis + 1) = alpha.cross(unit) + omega.cross(omega.cross(unit));
    moment.col(axis + 1) = unit.cross(accel);
  }
  Eigen::Matrix<double, Eigen::Dynamic, 4> regressor = Eigen::Matrix<double, Eigen::Dynamic, 4>::Zero(model.dof(), 4);
  const auto& links = model.links();
  for (int l = tip; l >= 0; l = links[l].parent) {
    if (links[l].joint >= 0) regressor.row(links[l].joint) = links[l].axis.transpose() * moment;
    if (links[l].parent < 0) break;
    const Eigen::Matrix3d& rotation = data.rotationToParent[l];
    const Eigen::Matrix<double, 3, 4> forceInParent = rotation * force;
    Eigen::Matrix<double, 3, 4> momentInParent = rotation * moment;
    const Eigen::Vector3d offset = links[l].originInParent.translation();
    for (int c = 0; c < 4; ++c) momentInParent.col(c) += offset.cross(forceInParent.col(c));
    force = forceInParent;
    moment = momentInParent;
  }
  return regressor;
}

}  // namespace arcplan::robot
