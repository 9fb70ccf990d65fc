// The joint-limit rule (robot/joint_limits.h) on arcplan's UR10e. Expected limits are the numbers
// written in data/ur10e/ur10e.urdf: ±2π for every joint but the elbow, ±π for the elbow (joint 2).
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/robot/joint_limits.h"
#include "support/error_message.h"

namespace {

using arcplan::robot::firstJointOutsideLimits;
using arcplan::robot::ur10e;

constexpr double kElbowLimit = 3.141592653589793;  // the URDF's text for joint 2's upper limit

Eigen::VectorXd zeros() { return Eigen::VectorXd::Zero(6); }

TEST(JointLimits, ALimitItselfIsWithinAndTheNextDoubleIsNot) {
  Eigen::VectorXd q = zeros();
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), std::nullopt);
  q[2] = kElbowLimit;
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), std::nullopt);
  q[2] = -kElbowLimit;
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), std::nullopt);
  q[2] = std::nextafter(kElbowLimit, 4.0);
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), 2);
  q[2] = std::nextafter(-kElbowLimit, -4.0);
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), 2);
  // 4 rad is within joint 0's ±2π, outside the elbow's ±π.
  q = zeros();
  q[0] = 4.0;
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), std::nullopt);
  q[0] = 6.3;  // > 2π = 6.2831853...
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), 0);
}

TEST(JointLimits, TheFirstJointOutsideIsNamed) {
  Eigen::VectorXd q = zeros();
  q[4] = -7.0;
  q[5] = 7.0;
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), 4);
}

TEST(JointLimits, ToleranceWidensBothSides) {
  Eigen::VectorXd q = zeros();
  q[2] = kElbowLimit + 5e-10;
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), 2);
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q, 1e-9), std::nullopt);
  q[2] = -kElbowLimit - 5e-10;
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q, 1e-9), std::nullopt);
  q[2] = kElbowLimit + 2e-9;
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q, 1e-9), 2);
}

TEST(JointLimits, NanAndInfinityAreOutside) {
  Eigen::VectorXd q = zeros();
  q[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), 1);
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q, 1.0), 1);
  q[1] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), 1);
  q[1] = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(firstJointOutsideLimits(ur10e(), q), 1);
}

TEST(JointLimits, AVectorOfTheWrongLengthIsAnError) {
  const std::string message =
      arcplan::testing::errorMessageOf([] { firstJointOutsideLimits(ur10e(), Eigen::VectorXd::Zero(5)); });
  EXPECT_NE(message.find("has 6 joints, but the joint vector has 5 values"), std::string::npos) << message;
}

TEST(JointLimits, TheTextNamesJointValueAndLimits) {
  EXPECT_EQ(arcplan::robot::outsideLimitsText(ur10e(), 2, 3.5, "joint 2"),
            "joint 2 (elbow_joint) = 3.5 rad is outside its limits [-3.14159265, 3.14159265]");
  EXPECT_EQ(arcplan::robot::outsideLimitsText(ur10e(), 0, -6.5, "q0"),
            "q0 (shoulder_pan_joint) = -6.5 rad is outside its limits [-6.28318531, 6.28318531]");
}

}  // namespace
