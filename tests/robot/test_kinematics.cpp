#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/pose.h"

namespace {

using arcplan::robot::ur10e;

// Standard DH link transform, written here independently of the library.
Eigen::Matrix4d dh(double theta, double d, double a, double alpha) {
  Eigen::Matrix4d t;
  t << std::cos(theta), -std::sin(theta) * std::cos(alpha), std::sin(theta) * std::sin(alpha), a * std::cos(theta),
      std::sin(theta), std::cos(theta) * std::cos(alpha), -std::cos(theta) * std::sin(alpha), a * std::sin(theta), 0,
      std::sin(alpha), std::cos(alpha), d, 0, 0, 0, 1;
  return t;
}

// ur10e-facts §1.1 DH table; base_link is the DH base frame rotated by pi about z (§1.2).
Eigen::Matrix4d dhTool0InBaseLink(const Eigen::VectorXd& q) {
  Eigen::Matrix4d baseLinkToBase = Eigen::Matrix4d::Identity();
  baseLinkToBase.block<2, 2>(0, 0) << -1, 0, 0, -1;
  return baseLinkToBase * dh(q[0], 0.1807, 0, M_PI_2) * dh(q[1], 0, -0.6127, 0) * dh(q[2], 0, -0.57155, 0) *
         dh(q[3], 0.17415, 0, M_PI_2) * dh(q[4], 0.11985, 0, -M_PI_2) * dh(q[5], 0.11655, 0, 0);
}

Eigen::VectorXd randomConfiguration(std::mt19937& random) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  Eigen::VectorXd q(6);
  for (auto& v : q) v = angle(random);
  return q;
}

TEST(ForwardKinematics, ZeroConfiguration) {
  const auto pose = arcplan::robot::tipPose(ur10e(), Eigen::VectorXd::Zero(6));
  // (-(a2+a3), d4+d6, d1-d5) from the DH numbers.
  EXPECT_NEAR(pose.translation().x(), 0.6127 + 0.57155, 1e-12);
  EXPECT_NEAR(pose.translation().y(), 0.17415 + 0.11655, 1e-12);
  EXPECT_NEAR(pose.translation().z(), 0.1807 - 0.11985, 1e-12);
  // tool0 axes at q = 0 (facts §1.3): x = (-1,0,0), y = (0,0,1), z = (0,1,0).
  Eigen::Matrix3d expected;
  expected << -1, 0, 0, 0, 0, 1, 0, 1, 0;
  EXPECT_LT((pose.linear() - expected).norm(), 1e-12);
}

TEST(ForwardKinematics, UpConfiguration) {
  Eigen::VectorXd q(6);
  q << 0, -M_PI_2, 0, -M_PI_2, 0, 0;
  const auto pose = arcplan::robot::tipPose(ur10e(), q);
  EXPECT_NEAR(pose.translation().x(), 0.0, 1e-12);
  EXPECT_NEAR(pose.translation().y(), 0.29070, 1e-12);
  EXPECT_NEAR(pose.translation().z(), 0.1807 + 0.6127 + 0.57155 + 0.11985, 1e-12);  // 1.48480
}

TEST(ForwardKinematics, UrdfChainEqualsDhProduct) {
  std::mt19937 random(5);
  for (int i = 0; i < 200; ++i) {
    const Eigen::VectorXd q = randomConfiguration(random);
    const Eigen::Matrix4d urdf = arcplan::robot::tipPose(ur10e(), q).matrix();
    EXPECT_LT((urdf - dhTool0InBaseLink(q)).norm(), 1e-12) << "q = " << q.transpose();
  }
}

TEST(ForwardKinematics, EveryLinkIsComputed) {
  const auto& model = ur10e();
  arcplan::robot::KinematicsData data(model);
  Eigen::VectorXd q(6);
  q << 0.3, -1.0, 1.2, -0.5, 0.7, 0.1;
  arcplan::robot::forwardKinematics(model, q, data);
  // The elbow sits a2 from the shoulder-lift axis, which is d1 above the base.
  const Eigen::Vector3d shoulder = data.linkPoses[model.linkIndex("upper_arm_link")].translation();
  const Eigen::Vector3d elbow = data.linkPoses[model.linkIndex("forearm_link")].translation();
  EXPECT_NEAR(shoulder.z(), 0.1807, 1e-12);
  EXPECT_NEAR((elbow - shoulder).norm(), 0.6127, 1e-12);
  // Fixed frames off the chain move rigidly: `base` is base_link turned by pi, flange = tool0 origin.
  EXPECT_NEAR(data.linkPoses[model.linkIndex("base")].linear()(0, 0), -1.0, 1e-12);
  EXPECT_LT(
      (data.linkPoses[model.linkIndex("flange")].translation() - data.linkPoses[model.tipLink()].translation()).norm(),
      1e-12);
}

TEST(Jacobian, MatchesFiniteDifferencesOfForwardKinematics) {
  const auto& model = ur10e();
  arcplan::robot::KinematicsData data(model);
  std::mt19937 random(9);
  const double step = 1e-6;
  // Also into a matrix kept across calls (the time scaling's), which must not keep what it held before.
  arcplan::robot::Jacobian reused = arcplan::robot::Jacobian::Constant(6, 6, 7.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = randomConfiguration(random);
    arcplan::robot::chainKinematics(model, q, model.tipLink(), data);
    arcplan::robot::jacobian(model, data, model.tipLink(), reused);
    const auto j = trial % 2 == 0 ? arcplan::robot::jacobian(model, data) : reused;
    for (int k = 0; k < 6; ++k) {
      Eigen::VectorXd plus = q, minus = q;
      plus[k] += step;
      minus[k] -= step;
      const auto tPlus = arcplan::robot::tipPose(model, plus), tMinus = arcplan::robot::tipPose(model, minus);
      const Eigen::Vector3d linear = (tPlus.translation() - tMinus.translation()) / (2 * step);
      const Eigen::AngleAxisd relative(tPlus.linear() * tMinus.linear().transpose());
      const Eigen::Vector3d angular = relative.axis() * relative.angle() / (2 * step);
      EXPECT_LT((j.block<3, 1>(0, k) - linear).norm(), 1e-7);
      EXPECT_LT((j.block<3, 1>(3, k) - angular).norm(), 1e-7);
    }
  }
}

}  // namespace
