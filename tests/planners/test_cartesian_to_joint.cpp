// TCP paths to joints on the start's IK branch: every waypoint reproduces its pose (FK), joint steps
// stay bounded, and each failure mode is reported with its reason.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <vector>

#include "arcplan/common/error.h"
#include "arcplan/planners/arc_path.h"
#include "arcplan/planners/cartesian_to_joint.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/robot_model.h"

namespace {

using arcplan::planners::ArcPath;
using arcplan::planners::checkConverted;
using arcplan::planners::ConversionStatus;
using arcplan::planners::convertToJoints;
using arcplan::planners::Detour;
using arcplan::planners::JointConversionOptions;
using arcplan::robot::Vector6;

const arcplan::robot::UrInverseKinematics& ik() {
  static const arcplan::robot::UrInverseKinematics solver(arcplan::robot::ur10e());
  return solver;
}

Eigen::Isometry3d thesisPose(double x, double y, double z) {
  return arcplan::robot::poseFromXyzRpy({x, y, z, 0.0, -M_PI, M_PI_2});
}

// ur10e-facts §6: elbow-up, wrist-down solutions of the thesis poses A and B.
Vector6 nearThesisStart() { return (Vector6() << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098).finished(); }
Vector6 nearThesisGoal() { return (Vector6() << 0.399, -1.624, 2.012, -1.958, -1.571, 0.399).finished(); }

Vector6 exactSolution(const Eigen::Isometry3d& pose, const Vector6& seed) { return *ik().solveNearest(pose, seed); }

const double kObstacleDistance = 0.375 * std::sqrt(0.6941);

TEST(CartesianToJoint, ThesisArcPathReproducesEveryPoseOnOneBranch) {
  const Eigen::Isometry3d a = thesisPose(0.4, -0.4, 0.25), b = thesisPose(0.5, 0.4, 0.46);
  const Vector6 start = exactSolution(a, nearThesisStart()), goal = exactSolution(b, nearThesisGoal());
  const ArcPath path(a, b, {Detour{kObstacleDistance, {0.1, 0.2, 0.1, 0.2}, 0.0}});
  JointConversionOptions options;
  options.resolution = 0.01;
  options.maxJointStep = 0.05;
  const auto result = convertToJoints(ik(), path, start, goal, options);
  ASSERT_TRUE(result.ok()) << result.reason;
  EXPECT_EQ(result.joints.front(), start);
  EXPECT_EQ(result.joints.back(), goal);
  ASSERT_EQ(result.joints.size(), result.arcLengths.size());
  EXPECT_GE(result.joints.size(), path.sample(options.resolution).size());
  const int branch = ik().branchOf(start);
  for (std::size_t i = 0; i < result.joints.size(); ++i) {
    const Eigen::Isometry3d reached = arcplan::robot::tipPose(arcplan::robot::ur10e(), result.joints[i]);
    const Eigen::Isometry3d wanted = path.pose(result.arcLengths[i]);
    EXPECT_LT((reached.translation() - wanted.translation()).norm(), 1e-9) << "waypoint " << i;
    EXPECT_LE(arcplan::robot::rotationDistance(reached.linear(), a.linear()), 1e-6) << "waypoint " << i;
    EXPECT_EQ(ik().branchOf(result.joints[i]), branch);
    if (i > 0) {
      EXPECT_LE((result.joints[i] - result.joints[i - 1]).cwiseAbs().maxCoeff(), options.maxJointStep);
      EXPECT_GT(result.arcLengths[i], result.arcLengths[i - 1]);
    }
  }
}

TEST(CartesianToJoint, LargeStepsAreBisectedAlongThePath) {
  const Eigen::Isometry3d a = thesisPose(0.4, -0.4, 0.25), b = thesisPose(0.5, 0.4, 0.46);
  const ArcPath path(a, b);
  JointConversionOptions options;
  options.resolution = 0.5;     // two samples: joint 0 turns ~1.5 rad over the line
  options.maxJointStep = 0.05;  // so the converter must insert points on the line
  const auto result = convertToJoints(ik(), path, exactSolution(a, nearThesisStart()), std::nullopt, options);
  ASSERT_TRUE(result.ok()) << result.reason;
  EXPECT_GT(result.joints.size(), 1.5 / 0.05);
  for (std::size_t i = 1; i < result.joints.size(); ++i) {
    EXPECT_LE((result.joints[i] - result.joints[i - 1]).cwiseAbs().maxCoeff(), options.maxJointStep);
    const Eigen::Vector3d tcp = arcplan::robot::tipPose(arcplan::robot::ur10e(), result.joints[i]).translation();
    EXPECT_LT((tcp - path.position(result.arcLengths[i])).norm(), 1e-9);
  }
}

TEST(CartesianToJoint, GoalOnAnotherBranchIsReportedAsBranchChange) {
  const Eigen::Isometry3d a = thesisPose(0.4, -0.4, 0.25), b = thesisPose(0.5, 0.4, 0.46);
  Vector6 otherBranchGoal = nearThesisGoal();
  for (const Vector6& candidate : ik().solveBranches(b)) {
    if (ik().branchOf(candidate) != ik().branchOf(nearThesisGoal())) otherBranchGoal = candidate;
  }
  ASSERT_NE(ik().branchOf(otherBranchGoal), ik().branchOf(nearThesisGoal()));
  const auto result = convertToJoints(ik(), ArcPath(a, b), exactSolution(a, nearThesisStart()), otherBranchGoal, {});
  EXPECT_EQ(result.status, ConversionStatus::BranchChange);
  EXPECT_NE(result.reason.find("branch"), std::string::npos) << result.reason;
}

TEST(CartesianToJoint, GoalInAnotherRepresentationIsReported) {
  const Eigen::Isometry3d a = thesisPose(0.4, -0.4, 0.25), b = thesisPose(0.5, 0.4, 0.46);
  Vector6 goal = exactSolution(b, nearThesisGoal());
  goal[5] -= 2.0 * M_PI;  // same pose, wrist 3 one turn further (inside its ±2·pi limits)
  const auto result = convertToJoints(ik(), ArcPath(a, b), exactSolution(a, nearThesisStart()), goal, {});
  EXPECT_EQ(result.status, ConversionStatus::GoalMismatch);
  EXPECT_NE(result.reason.find("2*pi"), std::string::npos) << result.reason;
}

TEST(CartesianToJoint, OutOfReachIsReportedWithItsArcLength) {
  const Eigen::Isometry3d a = thesisPose(0.4, -0.4, 0.25), far = thesisPose(2.4, -0.4, 0.25);
  const auto result = convertToJoints(ik(), ArcPath(a, far), exactSolution(a, nearThesisStart()), std::nullopt, {});
  EXPECT_EQ(result.status, ConversionStatus::Unreachable);
  // Reach of the wrist centre is about a2 + a3 = 1.18 m from the shoulder: fails well before 2 m.
  EXPECT_GT(result.failedAtArcLength, 0.5);
  EXPECT_LT(result.failedAtArcLength, 1.5);
  EXPECT_NE(result.reason.find("out of reach"), std::string::npos) << result.reason;
}

TEST(CartesianToJoint, StepAboveTheBoundAfterBisectionIsAJointJump) {
  const Eigen::Isometry3d a = thesisPose(0.4, -0.4, 0.25), b = thesisPose(0.5, 0.4, 0.46);
  JointConversionOptions options;
  options.resolution = 0.05;
  options.maxJointStep = 1e-3;
  options.maxBisections = 1;
  const auto result = convertToJoints(ik(), ArcPath(a, b), exactSolution(a, nearThesisStart()), std::nullopt, options);
  EXPECT_EQ(result.status, ConversionStatus::JointJump);
  EXPECT_NE(result.reason.find("would jump"), std::string::npos) << result.reason;
}

TEST(CartesianToJoint, PartOfThePathStartsFromItsSeed) {
  const Eigen::Isometry3d a = thesisPose(0.4, -0.4, 0.25), b = thesisPose(0.5, 0.4, 0.46);
  const ArcPath path(a, b, {Detour{kObstacleDistance, {0.1, 0.2, 0.1, 0.2}, 0.0}});
  const auto junctions = path.junctions();
  const Vector6 seed = exactSolution(path.pose(junctions[1]), nearThesisStart());
  const auto part = convertToJoints(ik(), path, seed, std::nullopt, {}, junctions[1], junctions[4]);
  ASSERT_TRUE(part.ok()) << part.reason;
  EXPECT_EQ(part.joints.front(), seed);
  EXPECT_DOUBLE_EQ(part.arcLengths.front(), junctions[1]);
  EXPECT_NEAR(part.arcLengths.back(), junctions[4], 1e-12);
}

TEST(CartesianToJoint, BranchChangeNamesTheBranchesAndTheirDifference) {
  // Branch bits (UrInverseKinematics::branchOf): 1 shoulder, 2 wrist (sin q5 < 0), 4 elbow (sin q3 < 0).
  const std::string elbow = arcplan::planners::describeBranchChange(1, 5);
  EXPECT_NE(elbow.find("branch 1 (shoulder solution 1, sin q5 >= 0, sin q3 >= 0)"), std::string::npos) << elbow;
  EXPECT_NE(elbow.find("branch 5 (shoulder solution 1, sin q5 >= 0, sin q3 < 0)"), std::string::npos) << elbow;
  EXPECT_NE(elbow.find("differ in the elbow (only through the singularity q3 = 0"), std::string::npos) << elbow;
  EXPECT_EQ(elbow.find("the wrist"), std::string::npos) << elbow;
  EXPECT_EQ(elbow.find("the shoulder"), std::string::npos) << elbow;
  const std::string all = arcplan::planners::describeBranchChange(0, 7);
  for (const char* part : {"the shoulder", "the wrist", "the elbow"})
    EXPECT_NE(all.find(part), std::string::npos) << all;
}

// checkConverted against the conversion run with the check (the second method): for checks that accept everything,
// refuse the first waypoint, one in the middle or the arrival (the goal configuration), and for conversions that
// fail on their own (out of reach, the goal in another representation), the same waypoints, status, reason, refused
// waypoint and arc length, and the check asked the same (previous, waypoint, arc length) in the same order.
TEST(CartesianToJoint, CheckingAConversionAgainEqualsConvertingWithTheCheck) {
  const Eigen::Isometry3d a = thesisPose(0.4, -0.4, 0.25), b = thesisPose(0.5, 0.4, 0.46);
  const Vector6 start = exactSolution(a, nearThesisStart()), goal = exactSolution(b, nearThesisGoal());
  const ArcPath detour(a, b, {Detour{kObstacleDistance, {0.1, 0.2, 0.1, 0.2}, 0.0}});
  const ArcPath outOfReach(a, thesisPose(2.4, -0.4, 0.25));
  Vector6 otherTurn = goal;
  otherTurn[5] -= 2.0 * M_PI;  // the goal pose in another representation: fails on arrival
  struct Case {
    const ArcPath& path;
    std::optional<Vector6> goal;
  };
  const ArcPath line(a, b);
  const Case cases[] = {{detour, goal}, {outOfReach, std::nullopt}, {line, otherTurn}};
  using Call = std::tuple<Vector6, Vector6, double>;
  for (const Case& c : cases) {
    const auto unchecked = convertToJoints(ik(), c.path, start, c.goal, {});
    ASSERT_GE(unchecked.joints.size(), 3u);
    const double arrival = unchecked.arcLengths.back();
    for (const double refuseFrom : {std::numeric_limits<double>::infinity(), 0.0, arrival / 2.0, arrival}) {
      std::vector<Call> direct, again;
      const auto checkRecording = [&](std::vector<Call>& calls) {
        return [&calls, refuseFrom](const Vector6& previous, const Vector6& q, double arcLength) {
          calls.emplace_back(previous, q, arcLength);
          return arcLength < refuseFrom;
        };
      };
      const auto expected = convertToJoints(ik(), c.path, start, c.goal, {}, 0.0,
                                            std::numeric_limits<double>::infinity(), checkRecording(direct));
      const auto result = checkConverted(unchecked, c.path, checkRecording(again));
      EXPECT_EQ(result.status, expected.status) << expected.reason;
      EXPECT_EQ(result.reason, expected.reason);
      EXPECT_EQ(result.joints, expected.joints);
      EXPECT_EQ(result.arcLengths, expected.arcLengths);
      EXPECT_EQ(result.refused, expected.refused);
      EXPECT_EQ(std::isnan(result.failedAtArcLength), std::isnan(expected.failedAtArcLength));
      if (!std::isnan(expected.failedAtArcLength)) {
        EXPECT_EQ(result.failedAtArcLength, expected.failedAtArcLength);
      }
      EXPECT_EQ(again, direct);
    }
  }
}

TEST(CartesianToJoint, CheckingAConversionWithoutItsSeedIsAClearError) {
  const Eigen::Isometry3d a = thesisPose(0.4, -0.4, 0.25), b = thesisPose(0.5, 0.4, 0.46);
  arcplan::planners::JointConversionResult broken;
  EXPECT_THROW(checkConverted(broken, ArcPath(a, b), {}), arcplan::Error);
  broken.joints.push_back(exactSolution(a, nearThesisStart()));
  EXPECT_THROW(checkConverted(broken, ArcPath(a, b), {}), arcplan::Error);  // no arc length for it
  broken.arcLengths.push_back(0.0);
  EXPECT_EQ(checkConverted(broken, ArcPath(a, b), {}).joints.size(), 1u);
}

}  // namespace
