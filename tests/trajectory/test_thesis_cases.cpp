// The thesis' four trajectories (seed chapter 4, Tables 4.3–4.5): case (a) the straight TCP line
// A→B, cases (b)–(d) the arc detours over the particle O with h = 1.00r, 0.75r, 0.50r, built by the
// planners module (ArcPath + analytic IK), then PCHIP-scaled here. Expected values: the issue's
// limits, the thesis table data/thesis/trajectory_results.csv, and the ramp kinematics L/v + T_rise.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "arcplan/collision/joint_states.h"
#include "arcplan/common/text_parsing.h"
#include "arcplan/planners/arc_path.h"
#include "arcplan/planners/cartesian_to_joint.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/trajectory/metrics.h"
#include "arcplan/trajectory/time_scaling.h"
#include "straight_line.h"

namespace arcplan::trajectory {
namespace {

struct ThesisCase {
  char name;
  double sagittaOverHalfChord;  // 0: no detour (case a)
  double analyticLength;        // the analytic arc length (Table 3.3 geometry, docs/planners.md), m
};
const ThesisCase kCases[] = {{'a', 0.0, 0.8331}, {'b', 1.00, 0.9920}, {'c', 0.75, 0.9321}, {'d', 0.50, 0.8825}};
const double kSpeeds[] = {0.149, 0.200, 0.250};

planners::ArcPath thesisTcpPath(const ThesisCase& thesisCase) {
  const Eigen::Isometry3d a = testing::thesisPoseA(), b = testing::thesisPoseB();
  std::vector<planners::Detour> detours;
  if (thesisCase.sagittaOverHalfChord > 0.0) {
    planners::Detour detour;
    // O on the line at y = -0.1: 0.3 of the line's 0.8 m extent in y.
    detour.position = 0.375 * (b.translation() - a.translation()).norm();
    detour.shape = {thesisCase.sagittaOverHalfChord * 0.2, 0.2, 0.1, 0.2};  // h, r, R2 = 0.5r, R3 = r
    detours.push_back(detour);
  }
  return planners::ArcPath(a, b, detours);
}

JointPath thesisJointPath(const ThesisCase& thesisCase) {
  const auto& model = robot::ur10e();
  const robot::UrInverseKinematics ik(model);
  const auto start = ik.solveNearest(testing::thesisPoseA(), testing::thesisSeedA());
  if (!start) throw std::runtime_error("no IK solution at A");
  const auto joints = planners::convertToJoints(ik, thesisTcpPath(thesisCase), *start, std::nullopt, {});
  if (!joints.ok()) throw std::runtime_error("joint conversion failed: " + joints.reason);
  return joints.joints;
}

struct ScaledCase {
  TrajectoryMetrics metrics;
  double speedLimit = 0.0;
};

// Every case at every thesis speed, computed once for all tests of this file.
const std::map<std::pair<char, double>, ScaledCase>& scaledCases() {
  static const auto cases = [] {
    std::map<std::pair<char, double>, ScaledCase> result;
    for (const auto& thesisCase : kCases) {
      const JointPath path = thesisJointPath(thesisCase);
      for (const double speed : kSpeeds) {
        TimeScalingOptions options;
        options.maxTcpSpeed = speed;
        const TimedTrajectory trajectory = scaleToTcpSpeed(robot::ur10e(), path, options);
        result[{thesisCase.name, speed}] = {computeMetrics(path, trajectory), speed};
      }
    }
    return result;
  }();
  return cases;
}

const TrajectoryMetrics& metricsOf(char name, double speed) { return scaledCases().at({name, speed}).metrics; }

// Thesis total times of the PCHIP runs on the real UR10e: case -> time, for one input speed.
std::map<char, double> thesisTimes(double speed) {
  std::ifstream in(std::string(ARCPLAN_TEST_DATA_DIR) + "/thesis/trajectory_results.csv");
  std::map<char, double> times;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      EXPECT_EQ(line.substr(0, 36), "case,h_over_r,source,v_in_mps,distan");
      header = false;
      continue;
    }
    const auto fields = splitFields(line, ',');  // case,h_over_r,source,v_in,distance,total_time,...
    if (fields[2] != "pchip_real" || std::abs(parseDouble(fields[3]).value_or(-1.0) - speed) > 1e-9) continue;
    times[fields[0][0]] = parseDouble(fields[5]).value();
  }
  return times;
}

std::string orderByTime(const std::map<char, double>& times) {
  std::string order;
  for (const auto& [name, time] : times) order += name;
  std::sort(order.begin(), order.end(), [&](char x, char y) { return times.at(x) > times.at(y); });
  return order;
}

TEST(ThesisCases, TcpPathLengthsMatchTheArcGeometry) {
  for (const auto& thesisCase : kCases) {
    // The densified path's TCP chords converge to the analytic arc length (docs/planners.md).
    EXPECT_NEAR(metricsOf(thesisCase.name, 0.25).tcpPathLength, thesisCase.analyticLength, 0.0005)
        << "case " << thesisCase.name;
  }
}

TEST(ThesisCases, NoSampleAboveTheCollaborativeLimit) {
  for (const auto& thesisCase : kCases) {
    const auto& metrics = metricsOf(thesisCase.name, 0.25);
    EXPECT_LE(metrics.peakTcpSpeed, 0.250) << "case " << thesisCase.name;  // the thesis saw 0.26
    EXPECT_EQ(metrics.timeAboveLimit, 0.0) << "case " << thesisCase.name;
    EXPECT_LE(metrics.maxJointSpeedRatio, 1.0);
  }
}

TEST(ThesisCases, ExecutionTimesAtTheCollaborativeLimit) {
  const double straight = metricsOf('a', 0.25).executionTime;
  const double lowArc = metricsOf('d', 0.25).executionTime;
  EXPECT_LE(straight, 3.55);           // thesis: 3.5 s measured
  EXPECT_LE(lowArc, 3.75);             // thesis: 3.95 s
  EXPECT_LE(lowArc - straight, 0.22);  // thesis: 0.45 s
  EXPECT_GT(metricsOf('b', 0.25).executionTime, metricsOf('c', 0.25).executionTime);
  EXPECT_GT(metricsOf('c', 0.25).executionTime, lowArc);
  EXPECT_GT(lowArc, straight);
}

TEST(ThesisCases, NothingIsFasterThanTheRampKinematicsAllow) {
  // With ramps of 0.2 s at constant acceleration, L/v + 0.2 s is the shortest possible time.
  for (const auto& [key, scaled] : scaledCases()) {
    EXPECT_GE(scaled.metrics.executionTime, scaled.metrics.tcpPathLength / scaled.speedLimit + 0.2 - 1e-6)
        << "case " << key.first << " at " << key.second;
  }
}

TEST(ThesisCases, MeanSpeedAndOrderOfTimesAtEveryThesisSpeed) {
  for (const double speed : kSpeeds) {
    std::map<char, double> ours;
    for (const auto& thesisCase : kCases) {
      const auto& metrics = metricsOf(thesisCase.name, speed);
      EXPECT_GE(metrics.meanTcpSpeed, 0.93 * speed)
          << "case " << thesisCase.name << " at " << speed;  // thesis 0.89–0.98
      EXPECT_LE(metrics.peakTcpSpeed, speed);
      ours[thesisCase.name] = metrics.executionTime;
    }
    const auto thesis = thesisTimes(speed);
    ASSERT_EQ(thesis.size(), 4u) << "thesis table rows for " << speed;
    EXPECT_EQ(orderByTime(ours), orderByTime(thesis)) << "at " << speed << " m/s";
  }
}

TEST(ThesisCases, SparseRrtConnectPathRespectsTheLimits) {
  // A real OMPL RRTConnect path (raw, unsimplified: few waypoints far apart) around a 0.15 m ball
  // about the thesis particle O that the TCP must avoid, with a fixed seed.
  namespace ob = ompl::base;
  namespace og = ompl::geometric;
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::RNG::setSeed(7);
  const auto& model = robot::ur10e();
  auto space = std::make_shared<ob::RealVectorStateSpace>(6);
  ob::RealVectorBounds bounds(6);
  for (int j = 0; j < 6; ++j) {
    bounds.setLow(j, model.joints()[j].limits.lower);
    bounds.setHigh(j, model.joints()[j].limits.upper);
  }
  space->setBounds(bounds);
  og::SimpleSetup setup(space);
  const Eigen::Vector3d obstacle(0.4375, -0.1, 0.32875);
  setup.setStateValidityChecker([&](const ob::State* state) {
    const robot::Vector6 q = collision::jointsOf(state, 6);
    return (robot::tipPose(model, q).translation() - obstacle).norm() > 0.15;
  });
  setup.getSpaceInformation()->setStateValidityCheckingResolution(0.002);
  const robot::UrInverseKinematics ik(model);
  const robot::Vector6 start = *ik.solveNearest(testing::thesisPoseA(), testing::thesisSeedA());
  robot::Vector6 goalSeed;
  goalSeed << 0.399, -1.624, 2.012, -1.958, -1.571, 0.399;
  const robot::Vector6 goal = *ik.solveNearest(testing::thesisPoseB(), goalSeed);
  ob::ScopedState<> startState(space), goalState(space);
  for (int j = 0; j < 6; ++j) {
    startState[j] = start[j];
    goalState[j] = goal[j];
  }
  setup.setStartAndGoalStates(startState, goalState);
  setup.setPlanner(std::make_shared<og::RRTConnect>(setup.getSpaceInformation()));
  ASSERT_TRUE(setup.solve(10.0));
  ASSERT_TRUE(setup.haveExactSolutionPath());
  const JointPath path = collision::waypointsOf(setup.getSolutionPath());
  ASSERT_GE(path.size(), 3u) << "the ball must force a detour";

  const TimedTrajectory trajectory = scaleToTcpSpeed(model, path, {});
  const TrajectoryMetrics metrics = computeMetrics(path, trajectory);
  EXPECT_LE(metrics.peakTcpSpeed, 0.25);
  EXPECT_EQ(metrics.timeAboveLimit, 0.0);
  EXPECT_LE(metrics.maxJointSpeedRatio, 1.0);
  EXPECT_GT(metrics.executionTime, metrics.tcpPathLength / 0.25);
  EXPECT_EQ(trajectory.position.back(), path.back());
  EXPECT_EQ(trajectory.position.front(), path.front());
}

}  // namespace
}  // namespace arcplan::trajectory
