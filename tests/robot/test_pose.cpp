#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "arcplan/robot/pose.h"

namespace {

using arcplan::robot::rotationDistance;
using arcplan::robot::rotationFromRpy;

Eigen::Matrix3d rotX(double a) {
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return r;
}
Eigen::Matrix3d rotY(double a) {
  Eigen::Matrix3d r;
  r << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return r;
}
Eigen::Matrix3d rotZ(double a) {
  Eigen::Matrix3d r;
  r << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return r;
}

TEST(Pose, RpyIsFixedAxisXyz) {
  const double roll = 0.3, pitch = -0.7, yaw = 2.1;
  EXPECT_TRUE(rotationFromRpy(roll, pitch, yaw).isApprox(rotZ(yaw) * rotY(pitch) * rotX(roll), 1e-14));
}

TEST(Pose, ThesisToolDownOrientation) {
  // ur10e-facts §6: rpy (0, -pi, pi/2) is tool z straight down, x = -y_ref, y = -x_ref.
  Eigen::Matrix3d expected;
  expected << 0, -1, 0, -1, 0, 0, 0, 0, -1;
  EXPECT_LT((rotationFromRpy(0, -M_PI, M_PI_2) - expected).norm(), 1e-12);
  // The same rotation has another RPY triple: compare rotations, not triples.
  EXPECT_LT(rotationDistance(rotationFromRpy(0, -M_PI, M_PI_2), rotationFromRpy(M_PI, 0, -M_PI_2)), 1e-12);
}

TEST(Pose, RpyRoundTripOnRandomRotations) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Matrix3d r = rotationFromRpy(angle(random), angle(random) / 2.0, angle(random));
    const Eigen::Vector3d rpy = arcplan::robot::rpyFromRotation(r);
    EXPECT_LT(rotationDistance(r, rotationFromRpy(rpy.x(), rpy.y(), rpy.z())), 1e-12);
  }
  // Gimbal lock (pitch = ±pi/2) still round-trips.
  const Eigen::Matrix3d locked = rotationFromRpy(0.4, M_PI_2, -0.3);
  const Eigen::Vector3d rpy = arcplan::robot::rpyFromRotation(locked);
  EXPECT_LT(rotationDistance(locked, rotationFromRpy(rpy.x(), rpy.y(), rpy.z())), 1e-7);
}

TEST(Pose, RotationDistanceIsTheRelativeAngle) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
  const Eigen::Matrix3d a = rotationFromRpy(0.2, 0.1, -1.0);
  for (const double angle : {0.0, 1e-9, 0.3, 2.0, M_PI - 1e-6, M_PI}) {
    const Eigen::Matrix3d b = a * Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    EXPECT_NEAR(rotationDistance(a, b), angle, 1e-9) << "angle " << angle;
  }
}

TEST(Pose, XyzRpyPoseRoundTrip) {
  const std::array<double, 6> values{0.4, -0.4, 0.25, 0.1, -0.2, 0.3};
  const auto pose = arcplan::robot::poseFromXyzRpy(values);
  const auto back = arcplan::robot::xyzRpyFromPose(pose);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(back[i], values[i], 1e-12);
}

}  // namespace
