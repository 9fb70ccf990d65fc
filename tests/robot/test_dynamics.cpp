// Rigid-body dynamics checked against computations that do not use Newton–Euler: energies from
// forward kinematics and Jacobians, differentiated numerically (Lagrange), and a pendulum formula.
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "arcplan/robot/dynamics.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/robot_model.h"

namespace {

using arcplan::robot::DynamicsData;
using arcplan::robot::DynamicsParameters;
using arcplan::robot::KinematicsData;
using arcplan::robot::RobotModel;
using Eigen::Vector3d;
using Eigen::VectorXd;

const Vector3d kGravity(0.0, 0.0, -9.81);

VectorXd randomJoints(std::mt19937& random, double scale) {
  std::uniform_real_distribution<double> value(-scale, scale);
  VectorXd q(6);
  for (int j = 0; j < 6; ++j) q[j] = value(random);
  return q;
}

// World position of a point given in a link frame, and its linear Jacobian.
Eigen::Matrix<double, 3, Eigen::Dynamic> pointJacobian(const RobotModel& model, const KinematicsData& kin, int link,
                                                       const Vector3d& pointInLink) {
  const auto full = arcplan::robot::jacobian(model, kin, link);
  const Vector3d offset = kin.linkPoses[link].linear() * pointInLink;
  Eigen::Matrix<double, 3, Eigen::Dynamic> linear = full.topRows(3);
  for (int j = 0; j < model.dof(); ++j) linear.col(j) += full.block<3, 1>(3, j).cross(offset);
  return linear;
}

// T = Σ ½ m |v_com|² + ½ ωᵀ I ω, from forward kinematics and Jacobians only.
double kineticEnergy(const RobotModel& model, const VectorXd& q, const VectorXd& qd, const DynamicsParameters& p) {
  KinematicsData kin(model);
  arcplan::robot::forwardKinematics(model, q, kin);
  double energy = 0.0;
  for (int l = 0; l < static_cast<int>(model.links().size()); ++l) {
    const auto& link = model.links()[l];
    if (link.hasInertial) {
      const Vector3d v = pointJacobian(model, kin, l, link.inertial.centerOfMass) * qd;
      const Vector3d omega = arcplan::robot::jacobian(model, kin, l).bottomRows(3) * qd;
      const Eigen::Matrix3d rotation = kin.linkPoses[l].linear();
      const Eigen::Matrix3d inertiaWorld = rotation * link.inertial.inertiaAboutCom * rotation.transpose();
      energy += 0.5 * link.inertial.mass * v.squaredNorm() + 0.5 * omega.dot(inertiaWorld * omega);
    }
    if (l == model.tipLink() && p.payload.mass != 0.0) {
      const Vector3d v = pointJacobian(model, kin, l, p.payload.centerOfMass) * qd;
      energy += 0.5 * p.payload.mass * v.squaredNorm();
    }
  }
  return energy;
}

// V = -Σ m g·p_com.
double potentialEnergy(const RobotModel& model, const VectorXd& q, const DynamicsParameters& p) {
  KinematicsData kin(model);
  arcplan::robot::forwardKinematics(model, q, kin);
  double energy = 0.0;
  for (int l = 0; l < static_cast<int>(model.links().size()); ++l) {
    const auto& link = model.links()[l];
    if (link.hasInertial) energy -= link.inertial.mass * p.gravity.dot(kin.linkPoses[l] * link.inertial.centerOfMass);
    if (l == model.tipLink()) energy -= p.payload.mass * p.gravity.dot(kin.linkPoses[l] * p.payload.centerOfMass);
  }
  return energy;
}

VectorXd potentialGradient(const RobotModel& model, const VectorXd& q, const DynamicsParameters& p) {
  const double h = 1e-6;
  VectorXd gradient(6);
  for (int j = 0; j < 6; ++j) {
    VectorXd plus = q, minus = q;
    plus[j] += h;
    minus[j] -= h;
    gradient[j] = (potentialEnergy(model, plus, p) - potentialEnergy(model, minus, p)) / (2 * h);
  }
  return gradient;
}

DynamicsParameters withPayload() {
  DynamicsParameters p;
  p.payload.mass = 2.5;
  p.payload.centerOfMass = Vector3d(0.02, -0.01, 0.08);
  return p;
}

TEST(Dynamics, GravityTorqueIsTheGradientOfPotentialEnergy) {
  const auto& model = arcplan::robot::ur10e();
  DynamicsData data(model);
  std::mt19937 random(11);
  for (const auto& parameters : {DynamicsParameters{}, withPayload()}) {
    for (int trial = 0; trial < 10; ++trial) {
      const VectorXd q = randomJoints(random, M_PI);
      const VectorXd expected = potentialGradient(model, q, parameters);
      const VectorXd actual = arcplan::robot::gravityTorque(model, q, data, parameters);
      EXPECT_LT((actual - expected).cwiseAbs().maxCoeff(), 1e-5) << "q = " << q.transpose();
    }
  }
}

TEST(Dynamics, ShoulderCarriesTheArmWhenStretchedHorizontally) {
  // At q = 0 the UR10e arm lies horizontal; joints 1 and 2 hold the weight of everything beyond them.
  const auto& model = arcplan::robot::ur10e();
  DynamicsData data(model);
  const VectorXd tau = arcplan::robot::gravityTorque(model, VectorXd::Zero(6), data);
  EXPECT_NEAR(tau[0], 0.0, 1e-9);  // vertical axis: gravity does no work
  EXPECT_GT(std::abs(tau[1]), 100.0);
  EXPECT_GT(std::abs(tau[1]), std::abs(tau[2]));
}

TEST(Dynamics, MassMatrixIsTheHessianOfKineticEnergy) {
  const auto& model = arcplan::robot::ur10e();
  DynamicsData data(model);
  std::mt19937 random(12);
  for (const auto& parameters : {DynamicsParameters{}, withPayload()}) {
    for (int trial = 0; trial < 5; ++trial) {
      const VectorXd q = randomJoints(random, M_PI);
      const Eigen::MatrixXd mass = arcplan::robot::massMatrix(model, q, data, parameters);
      // T is quadratic in qd, so a central second difference is exact up to rounding.
      Eigen::MatrixXd hessian(6, 6);
      const double h = 1e-2;
      for (int i = 0; i < 6; ++i) {
        for (int k = 0; k < 6; ++k) {
          auto at = [&](double si, double sk) {
            VectorXd qd = VectorXd::Zero(6);
            qd[i] += si * h;
            qd[k] += sk * h;
            return kineticEnergy(model, q, qd, parameters);
          };
          hessian(i, k) = (at(1, 1) - at(1, -1) - at(-1, 1) + at(-1, -1)) / (4 * h * h);
        }
      }
      EXPECT_LT((mass - hessian).cwiseAbs().maxCoeff(), 1e-7);
      EXPECT_LT((mass - mass.transpose()).cwiseAbs().maxCoeff(), 1e-12);
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (mass + mass.transpose()));
      EXPECT_GT(eigen.eigenvalues().minCoeff(), 0.0);
    }
  }
}

TEST(Dynamics, InverseDynamicsSatisfiesLagrangesEquations) {
  // τ = d/dt ∂T/∂qd − ∂T/∂q + ∂V/∂q, every derivative taken numerically on the energies.
  const auto& model = arcplan::robot::ur10e();
  DynamicsData data(model);
  std::mt19937 random(13);
  const DynamicsParameters parameters = withPayload();
  for (int trial = 0; trial < 4; ++trial) {
    const VectorXd q = randomJoints(random, M_PI), qd = randomJoints(random, 1.5), qdd = randomJoints(random, 3.0);
    const double h = 1e-4;
    auto momentum = [&](const VectorXd& qAt, const VectorXd& qdAt) {
      VectorXd p(6);
      for (int j = 0; j < 6; ++j) {
        VectorXd plus = qdAt, minus = qdAt;
        plus[j] += h;
        minus[j] -= h;
        p[j] = (kineticEnergy(model, qAt, plus, parameters) - kineticEnergy(model, qAt, minus, parameters)) / (2 * h);
      }
      return p;
    };
    const VectorXd momentumRate = (momentum(q + h * qd + 0.5 * h * h * qdd, qd + h * qdd) -
                                   momentum(q - h * qd + 0.5 * h * h * qdd, qd - h * qdd)) /
                                  (2 * h);
    VectorXd kineticGradient(6);
    for (int j = 0; j < 6; ++j) {
      VectorXd plus = q, minus = q;
      plus[j] += h;
      minus[j] -= h;
      kineticGradient[j] =
          (kineticEnergy(model, plus, qd, parameters) - kineticEnergy(model, minus, qd, parameters)) / (2 * h);
    }
    const VectorXd expected = momentumRate - kineticGradient + potentialGradient(model, q, parameters);
    const VectorXd actual = arcplan::robot::inverseDynamics(model, q, qd, qdd, data, parameters);
    EXPECT_LT((actual - expected).cwiseAbs().maxCoeff(), 1e-5 * (1.0 + expected.cwiseAbs().maxCoeff()))
        << "expected " << expected.transpose() << "\nactual   " << actual.transpose();
  }
}

TEST(Dynamics, PowerBalanceAlongATrajectory) {
  // dE/dt = τ·qd for E = T + V on a smooth multi-sine motion of all six joints.
  const auto& model = arcplan::robot::ur10e();
  DynamicsData data(model);
  const DynamicsParameters parameters = withPayload();
  auto state = [](double t, VectorXd& q, VectorXd& qd, VectorXd& qdd) {
    q.resize(6), qd.resize(6), qdd.resize(6);
    for (int j = 0; j < 6; ++j) {
      const double w = 0.7 + 0.31 * j, a = 0.8 - 0.07 * j, phase = 0.5 * j;
      q[j] = a * std::sin(w * t + phase) - 0.3;
      qd[j] = a * w * std::cos(w * t + phase);
      qdd[j] = -a * w * w * std::sin(w * t + phase);
    }
  };
  auto energy = [&](double t) {
    VectorXd q, qd, qdd;
    state(t, q, qd, qdd);
    return kineticEnergy(model, q, qd, parameters) + potentialEnergy(model, q, parameters);
  };
  for (double t = 0.0; t < 6.0; t += 0.37) {
    VectorXd q, qd, qdd;
    state(t, q, qd, qdd);
    const double power = arcplan::robot::inverseDynamics(model, q, qd, qdd, data, parameters).dot(qd);
    const double h = 1e-4;
    const double energyRate = (energy(t + h) - energy(t - h)) / (2 * h);
    EXPECT_NEAR(power, energyRate, 1e-4 * (1.0 + std::abs(power))) << "t = " << t;
  }
}

TEST(Dynamics, SinglePendulumMatchesTheTextbookFormula) {
  // Point-like bob (tiny inertia) of mass m at distance l from a horizontal axis: τ = m l² qdd + m g l cos q.
  const std::string urdf = R"(<robot name="pendulum">
    <link name="base"/>
    <link name="arm"><inertial><origin xyz="0.7 0 0"/><mass value="3.0"/>
      <inertia ixx="1e-9" ixy="0" ixz="0" iyy="1e-9" iyz="0" izz="1e-9"/></inertial></link>
    <joint name="hinge" type="continuous"><parent link="base"/><child link="arm"/>
      <origin xyz="0 0 0.5" rpy="1.5707963267948966 0 0"/><axis xyz="0 0 1"/></joint>
  </robot>)";
  const RobotModel model = arcplan::robot::parseRobotModel(urdf, "pendulum.urdf", {"base", "arm", std::nullopt});
  DynamicsData data(model);
  for (double q : {-1.0, 0.0, 0.4, 2.0}) {
    const double qd = 1.3, qdd = -0.8, m = 3.0, l = 0.7, g = 9.81;
    const VectorXd tau = arcplan::robot::inverseDynamics(model, VectorXd::Constant(1, q), VectorXd::Constant(1, qd),
                                                         VectorXd::Constant(1, qdd), data);
    // Rotating about +x by 90° makes the joint axis -y in the base: positive q lifts the bob.
    EXPECT_NEAR(tau[0], m * l * l * qdd + m * g * l * std::cos(q), 1e-6) << "q = " << q;
  }
}

TEST(Dynamics, PayloadTorqueIsTheForceOnAPointMassThroughTheJacobian) {
  // A point mass needs the force m·(p̈ − g); the joints feel Jᵀ of it (p̈ from forward kinematics).
  const auto& model = arcplan::robot::ur10e();
  DynamicsData data(model);
  std::mt19937 random(14);
  const DynamicsParameters payload = withPayload();
  for (int trial = 0; trial < 4; ++trial) {
    const VectorXd q = randomJoints(random, M_PI), qd = randomJoints(random, 1.0), qdd = randomJoints(random, 2.0);
    auto position = [&](double t) {
      const VectorXd qt = q + t * qd + 0.5 * t * t * qdd;
      KinematicsData kin(model);
      arcplan::robot::forwardKinematics(model, qt, kin);
      return Vector3d(kin.linkPoses[model.tipLink()] * payload.payload.centerOfMass);
    };
    const double h = 1e-4;
    const Vector3d acceleration = (position(h) - 2 * position(0) + position(-h)) / (h * h);
    KinematicsData kin(model);
    arcplan::robot::forwardKinematics(model, q, kin);
    const auto linear = pointJacobian(model, kin, model.tipLink(), payload.payload.centerOfMass);
    const VectorXd expected = linear.transpose() * (payload.payload.mass * (acceleration - kGravity));
    const VectorXd actual = arcplan::robot::inverseDynamics(model, q, qd, qdd, data, payload) -
                            arcplan::robot::inverseDynamics(model, q, qd, qdd, data);
    EXPECT_LT((actual - expected).cwiseAbs().maxCoeff(), 1e-4) << "expected " << expected.transpose();

    // The regressor: exact for a mass at the tip origin; otherwise short only by the neglected
    // second moment, which we compute here as the moment of m·(α×c + ω×(ω×c)) about the tip origin.
    const auto regressor = arcplan::robot::payloadRegressor(model, q, qd, qdd, data);
    const double m = payload.payload.mass;
    const Eigen::Vector4d theta(m, m * payload.payload.centerOfMass.x(), m * payload.payload.centerOfMass.y(),
                                m * payload.payload.centerOfMass.z());
    const auto full = arcplan::robot::jacobian(model, kin, model.tipLink());
    const Vector3d omega = full.bottomRows(3) * qd;
    Eigen::Matrix<double, 6, 1> jdotQd;  // angular acceleration of the tip = J_w qdd + dJ_w/dt qd
    {
      KinematicsData ahead(model), behind(model);
      arcplan::robot::forwardKinematics(model, q + h * qd, ahead);
      arcplan::robot::forwardKinematics(model, q - h * qd, behind);
      jdotQd = (arcplan::robot::jacobian(model, ahead, model.tipLink()) -
                arcplan::robot::jacobian(model, behind, model.tipLink())) /
               (2 * h) * qd;
    }
    const Vector3d alpha = full.bottomRows(3) * qdd + jdotQd.tail<3>();
    const Vector3d c = kin.linkPoses[model.tipLink()].linear() * payload.payload.centerOfMass;
    const Vector3d secondMomentTorque = c.cross(m * (alpha.cross(c) + omega.cross(omega.cross(c))));
    const VectorXd neglected = full.bottomRows(3).transpose() * secondMomentTorque;
    EXPECT_LT((regressor * theta + neglected - expected).cwiseAbs().maxCoeff(), 1e-4);

    DynamicsParameters atOrigin;
    atOrigin.payload.mass = 1.7;
    const VectorXd originTorque = arcplan::robot::inverseDynamics(model, q, qd, qdd, data, atOrigin) -
                                  arcplan::robot::inverseDynamics(model, q, qd, qdd, data);
    EXPECT_LT((regressor.col(0) * 1.7 - originTorque).cwiseAbs().maxCoeff(), 1e-9);
  }
}

}  // namespace
