#include <cmath>
#include <fstream>
#include <random>
#include <regex>
#include <set>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/ur_inverse_kinematics.h"
#include "support/command.h"
#include "support/joint_states.h"
#include "support/robot_files.h"
#include "robot/ur_round_trips.h"

namespace {

using arcplan::robot::ur10e;
using arcplan::robot::ur10eUrdfPath;
using arcplan::robot::UrInverseKinematics;
using arcplan::robot::Vector6;
using arcplan::testing::angularDistanceModuloTwoPi;
using arcplan::testing::expectReproducesPose;
using arcplan::testing::randomJointState;

// Every one of `trials` seeded random configurations is among the IK solutions of its tip pose.
void expectRoundTrips(const arcplan::robot::RobotModel& model, unsigned seed, int trials, double tolerance) {
  EXPECT_EQ(arcplan::testing::urRoundTrips(model, seed, trials, tolerance), trials) << model.name();
}

TEST(UrInverseKinematics, ReadsTheDhParametersOffTheUrdf) {
  const UrInverseKinematics ik(ur10e());
  const auto& dh = ik.dhParameters();
  EXPECT_NEAR(dh.d1, 0.1807, 1e-12);
  EXPECT_NEAR(dh.a2, -0.6127, 1e-12);
  EXPECT_NEAR(dh.a3, -0.57155, 1e-12);
  EXPECT_NEAR(dh.d4, 0.17415, 1e-12);
  EXPECT_NEAR(dh.d5, 0.11985, 1e-12);
  EXPECT_NEAR(dh.d6, 0.11655, 1e-12);
}

TEST(UrInverseKinematics, ThousandRandomConfigurationsRoundTrip) { expectRoundTrips(ur10e(), 2024, 1000, 1e-9); }

TEST(UrInverseKinematics, SolveAllGivesEveryInLimitRepresentation) {
  const auto& model = ur10e();
  const UrInverseKinematics ik(model);
  // Thesis pose A has all 8 analytic branches (ur10e-facts §6).
  const auto target = arcplan::robot::poseFromXyzRpy({0.4, -0.4, 0.25, 0, -M_PI, M_PI_2});
  ASSERT_EQ(ik.solveBranches(target).size(), 8u);
  const auto all = ik.solveAll(target);
  // 8 branches; joints 0,1,3,4,5 with ±2pi limits have two representations each, the elbow one.
  EXPECT_EQ(all.size(), 8u * 32u);
  std::set<std::vector<long>> distinct;
  for (const auto& s : all) {
    arcplan::testing::expectWithinJointLimits(model, s);
    expectReproducesPose(model, s, target);
    std::vector<long> key;
    for (int j = 0; j < 6; ++j) key.push_back(std::lround(s[j] * 1e6));
    distinct.insert(key);
  }
  EXPECT_EQ(distinct.size(), all.size());
}

TEST(UrInverseKinematics, ThesisPoseAElbowUpWristDown) {
  const auto& model = ur10e();
  const UrInverseKinematics ik(model);
  const auto target = arcplan::robot::poseFromXyzRpy({0.4, -0.4, 0.25, 0, -M_PI, M_PI_2});
  Vector6 expected;
  expected << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098;  // ur10e-facts §6
  bool found = false;
  for (const auto& s : ik.solveBranches(target)) {
    expectReproducesPose(model, s, target);
    if (angularDistanceModuloTwoPi(s, expected) < 1e-3) found = true;
  }
  EXPECT_TRUE(found);
  const auto nearest = ik.solveNearest(target, expected);
  ASSERT_TRUE(nearest.has_value());
  EXPECT_LT((*nearest - expected).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(UrInverseKinematics, NearestPicksTheSeedsBranchAndRepresentation) {
  const auto& model = ur10e();
  const UrInverseKinematics ik(model);
  std::mt19937 random(77);
  for (int trial = 0; trial < 200; ++trial) {
    const Vector6 q = randomJointState(model, random);
    Vector6 seed = q;
    for (auto& v : seed) v += std::uniform_real_distribution<double>(-0.05, 0.05)(random);
    const auto nearest = ik.solveNearest(arcplan::robot::tipPose(model, q), seed);
    ASSERT_TRUE(nearest.has_value());
    EXPECT_LT((*nearest - q).cwiseAbs().maxCoeff(), 1e-7) << q.transpose();
    EXPECT_EQ(ik.branchOf(*nearest), ik.branchOf(q));
  }
}

TEST(UrInverseKinematics, BranchesAreDistinct) {
  const UrInverseKinematics ik(ur10e());
  std::set<int> branches;
  const auto poseB = arcplan::robot::poseFromXyzRpy({0.5, 0.4, 0.46, 0, -M_PI, M_PI_2});
  for (const auto& s : ik.solveBranches(poseB)) branches.insert(ik.branchOf(s));
  EXPECT_EQ(branches.size(), 8u);
}

TEST(UrInverseKinematics, WristSingularityUsesTheHint) {
  const auto& model = ur10e();
  const UrInverseKinematics ik(model);
  Vector6 q;
  q << 0.4, -1.3, 1.5, -0.9, 0.0, 0.7;  // q5 = 0: wrist-3 axis parallel to joints 2-4
  const auto target = arcplan::robot::tipPose(model, q);
  const auto solutions = ik.solveBranches(target, 0.25);
  ASSERT_FALSE(solutions.empty());
  for (const auto& s : solutions) {
    expectReproducesPose(model, s, target);
    if (std::abs(std::sin(s[4])) < 1e-6) {
      EXPECT_NEAR(s[5], 0.25, 1e-12);
    }
  }
}

TEST(UrInverseKinematics, OutOfReachGivesNoSolution) {
  const UrInverseKinematics ik(ur10e());
  EXPECT_TRUE(ik.solveBranches(arcplan::robot::poseFromXyzRpy({1.6, 0.2, 0.3, 0, -M_PI, 0})).empty());
  // Inside the d4-cylinder about the base axis the wrist cannot be placed either.
  EXPECT_TRUE(ik.solveBranches(arcplan::robot::poseFromXyzRpy({0.0, 0.05, 0.5, 0, -M_PI, 0})).empty());
}

// The description text (mesh paths absolute) written to a folder of its own.
std::filesystem::path writeVariant(const std::string& name, const std::string& text) {
  const auto dir = arcplan::testing::freshTempDirectory(name);
  std::ofstream(dir / "robot.urdf") << text;
  return dir / "robot.urdf";
}

TEST(UrInverseKinematics, WorksWithAToolFrameBeyondTheFlange) {
  std::string text = arcplan::testing::ur10eUrdfText();
  text.replace(text.rfind("</robot>"), 8,
               R"(<link name="gripper_tip"/><joint name="tool0-gripper_tip" type="fixed"><parent link="tool0"/>
<child link="gripper_tip"/><origin xyz="0.01 0 0.2" rpy="0 0 0.3"/></joint></robot>)");
  const auto model =
      arcplan::robot::loadRobotModel(writeVariant("gripper_tip", text), {"base_link", "gripper_tip", std::nullopt});
  expectRoundTrips(model, 3, 100, 1e-8);
}

TEST(UrInverseKinematics, WorksWithCalibrationDigitsOfTheRos2Description) {
  // The ROS 2 description writes pi/2 as 1.570796327 and has 1e-11 m offsets: no exact DH chain.
  std::string text = arcplan::testing::ur10eUrdfText();
  text = std::regex_replace(text, std::regex("xyz=\"0 -0.11985 0\""), "xyz=\"0 -0.11985 -2.458e-11\"");
  text = std::regex_replace(text, std::regex("<origin xyz=\"0 0 0\" rpy=\"1.570796326794897 0 0\"/>"),
                            "<origin xyz=\"0 0 0\" rpy=\"1.570796327 0 0\"/>");
  const auto model = arcplan::robot::loadRobotModel(writeVariant("calibration_digits", text));
  // Every pose of the arm is reachable; the same pose to 1e-9, but near a wrist singularity the joints
  // of a not-exactly-DH chain may differ by a few microradians (1.4e-6 rad seen), far below any branch
  // change.
  expectRoundTrips(model, 4, 200, 1e-4);
}

TEST(UrInverseKinematics, RejectsAChainThatIsNotUrType) {
  // Six parallel z axes: a planar arm, not a UR.
  std::string urdf = "<robot name=\"planar\"><link name=\"base_link\"/>";
  std::string parent = "base_link";
  for (int j = 0; j < 6; ++j) {
    const std::string child = j == 5 ? "tool0" : "l" + std::to_string(j);
    urdf += "<link name=\"" + child + "\"/><joint name=\"j" + std::to_string(j) +
            "\" type=\"revolute\"><parent link=\"" + parent + "\"/><child link=\"" + child +
            "\"/><origin xyz=\"0.3 0 0\"/><axis xyz=\"0 0 1\"/><limit lower=\"-3\" upper=\"3\" effort=\"1\" "
            "velocity=\"1\"/></joint>";
    parent = child;
  }
  urdf += "</robot>";
  const auto model = arcplan::robot::parseRobotModel(urdf, "planar.urdf");
  EXPECT_THROW(UrInverseKinematics{model}, arcplan::Error);
}

TEST(UrInverseKinematics, AMillimetreOffTheUrChainIsRefusedWithTheMismatchAndTolerance) {
  // Wrist 2 one millimetre off its UR place: no URDF rounding explains that.
  std::string text = arcplan::testing::ur10eUrdfText();
  const std::string wrist2 = "<origin xyz=\"0 -0.11985 0\"";
  ASSERT_NE(text.find(wrist2), std::string::npos);
  text.replace(text.find(wrist2), wrist2.size(), "<origin xyz=\"0.001 -0.11985 0\"");
  const auto model = arcplan::robot::loadRobotModel(writeVariant("millimetre_off", text));
  try {
    UrInverseKinematics{model};
    FAIL() << "accepted";
  } catch (const arcplan::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("is not a UR-type arm"), std::string::npos) << message;
    EXPECT_NE(message.find("tolerance 1e-06 m and rad"), std::string::npos) << message;
    // The tip moves by the offset at every configuration: the mismatch is about a millimetre.
    const std::size_t by = message.find("by ");
    ASSERT_NE(by, std::string::npos) << message;
    const double mismatch = std::stod(message.substr(by + 3));
    EXPECT_GT(mismatch, 0.5e-3) << message;
    EXPECT_LT(mismatch, 2.5e-3) << message;
  }
}

TEST(UrInverseKinematics, ArmStandingAnywhereInTheBaseFrame) {
  // The chain starts at a world frame; the arm stands at (1, 0.5, 0.2), turned by 0.7 rad and tilted.
  std::string text = arcplan::testing::ur10eUrdfText();
  text.replace(text.rfind("</robot>"), 8,
               R"(<link name="world"/><joint name="mount" type="fixed"><parent link="world"/>
<child link="base_link"/><origin xyz="1 0.5 0.2" rpy="0.1 0 0.7"/></joint></robot>)");
  const auto model = arcplan::robot::loadRobotModel(writeVariant("mounted", text), {"world", "tool0", std::nullopt});
  expectRoundTrips(model, 8, 100, 1e-9);
}

TEST(UrInverseKinematics, TcpOffsetIsTheTipItSolvesFor) {
  const Eigen::Isometry3d offset = arcplan::robot::poseFromXyzRpy({0.0, 0.02, 0.15, 0.0, 0.0, 0.4});
  const auto model = arcplan::robot::loadRobotModel(ur10eUrdfPath(), {"base_link", "tool0", offset});
  EXPECT_EQ(model.links()[model.tipLink()].name, "tcp");
  const UrInverseKinematics ik(model);
  std::mt19937 random(9);
  for (int trial = 0; trial < 100; ++trial) {
    const Vector6 q = randomJointState(model, random);
    // The TCP is tool0 (of arcplan's UR10e) times the offset.
    const auto target = arcplan::robot::tipPose(ur10e(), q) * offset;
    EXPECT_LT((arcplan::robot::tipPose(model, q).matrix() - target.matrix()).norm(), 1e-12);
    double closest = 1e9;
    for (const auto& s : ik.solveBranches(target)) closest = std::min(closest, angularDistanceModuloTwoPi(s, q));
    EXPECT_LT(closest, 1e-9);
  }
}

}  // namespace

namespace {

TEST(UrInverseKinematics, SolveBranchEqualsThatBranchOfSolveBranches) {
  const auto& model = arcplan::robot::ur10e();
  const UrInverseKinematics ik(model);
  std::mt19937 random(31);
  int compared = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vector6 q = randomJointState(model, random);
    const auto target = arcplan::robot::tipPose(model, q);
    const auto all = ik.solveBranches(target);
    for (int branch = 0; branch < 8; ++branch) {
      const auto single = ik.solveBranch(target, branch);
      const auto inAll =
          std::find_if(all.begin(), all.end(), [&](const Vector6& s) { return ik.branchOf(s) == branch; });
      ASSERT_EQ(single.has_value(), inAll != all.end()) << "branch " << branch;
      if (single) {
        EXPECT_EQ(ik.branchOf(*single), branch);
        EXPECT_LT((*single - *inAll).cwiseAbs().maxCoeff(), 1e-12);
        ++compared;
      }
    }
    // The original configuration is the solution of its own branch.
    const auto own = ik.solveBranch(target, ik.branchOf(q), q[5]);
    ASSERT_TRUE(own.has_value());
    EXPECT_LT(angularDistanceModuloTwoPi(*own, q), 1e-9);
  }
  EXPECT_GT(compared, 1500);
}

}  // namespace
