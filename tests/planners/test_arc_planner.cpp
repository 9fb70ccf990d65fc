// ArcPlanner as an OMPL planner: straight line when free, the thesis detour around the particle, chained
// detours, solid obstacles, the auto search, reasons for failure, the termination condition, planner data and
// ompl::tools::Benchmark (the fallback: test_arc_planner_fallback.cpp; the deadline: ..._limits.cpp).
#include <gtest/gtest.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/tools/benchmark/Benchmark.h>

#include <cmath>
#include <optional>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/common/error.h"
#include "arcplan/planners/arc_planner.h"
#include "arcplan/planners/blended_path.h"
#include "arcplan/planners/cartesian_to_joint.h"
#include "planners/planner_test_support.h"

namespace {

using arcplan::planners::ArcPlannerResult;
using namespace arcplan::testing;
namespace ob = ompl::base;

double distanceToLine(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = (b - a).normalized();
  return (p - a - (p - a).dot(d) * d).norm();
}

// thesis_free with extra obstacles.
arcplan::planners::PlanningProblem freeSceneWith(const std::vector<arcplan::collision::Obstacle>& obstacles) {
  auto scene = std::make_shared<arcplan::collision::Scene>(*loadTestScene("thesis_free"));
  for (const auto& obstacle : obstacles) scene->obstacles.push_back(obstacle);
  return arcplan::planners::makePlanningProblem(scene);
}

// Point of the thesis line A->B at y (the line is parametrised by y from -0.4 to 0.4).
Eigen::Vector3d thesisLinePoint(double y) { return thesisA() + (thesisB() - thesisA()) * ((y - thesisA().y()) / 0.8); }

TEST(ArcPlanner, FreeLineIsTheStraightTcpLine) {
  auto problem = thesisProblem("thesis_free");
  const auto [planner, status] = solve(problem, "arc");
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  EXPECT_EQ(arcOf(planner).lastResult().kind, ArcPlannerResult::Kind::StraightLine);
  const auto joints = arcplan::collision::waypointsOf(problem.setup->getSolutionPath());
  EXPECT_EQ(joints.front(), problem.start);
  EXPECT_EQ(joints.back(), problem.goal);
  const auto poses = tcpPoses(joints);
  double length = 0.0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_LT(distanceToLine(poses[i].translation(), thesisA(), thesisB()), 1e-9) << "waypoint " << i;
    EXPECT_LE(arcplan::robot::rotationDistance(poses[i].linear(), thesisToolDown()), 1e-6) << "waypoint " << i;
    if (i > 0) length += (poses[i].translation() - poses[i - 1].translation()).norm();
  }
  EXPECT_NEAR(length, 0.8331, 5e-5);  // thesis Table 3.3, case (a)
  EXPECT_TRUE(problem.setup->getSolutionPath().check());
}

TEST(ArcPlanner, ThesisParticleGetsTheGivenDetourAtO) {
  auto problem = thesisProblem("thesis_obstacle");
  const auto [planner, status] = solve(
      problem, "arc", {{"sagitta", "0.1"}, {"half_chord", "0.2"}, {"entry_radius", "0.1"}, {"exit_radius", "0.2"}});
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  const auto& result = arcOf(planner).lastResult();
  EXPECT_EQ(result.kind, ArcPlannerResult::Kind::Detour);
  ASSERT_EQ(result.detours.size(), 1u);
  EXPECT_EQ(result.obstacles, std::vector<std::string>{"particle"});
  // O is the particle itself: on the line at y = -0.1, 0.375 of the way from A.
  EXPECT_NEAR(result.detours[0].position, 0.375 * (thesisB() - thesisA()).norm(), 1e-12);
  EXPECT_DOUBLE_EQ(result.detours[0].shape.sagitta, 0.1);
  EXPECT_DOUBLE_EQ(result.detours[0].planeAngle, 0.0);
  // The straight line really is blocked for the whole robot (independently of the planner).
  const arcplan::robot::UrInverseKinematics ik(arcplan::robot::ur10e());
  const arcplan::planners::ArcPath line(tcpPoses({problem.start})[0], tcpPoses({problem.goal})[0]);
  const auto lineJoints = arcplan::planners::convertToJoints(ik, line, problem.start, problem.goal, {});
  ASSERT_TRUE(lineJoints.ok());
  arcplan::collision::CollisionData data(*problem.collisionModel);
  bool hitsParticle = false;
  for (const auto& q : lineJoints.joints) {
    for (const auto& pair : arcplan::collision::collide(*problem.collisionModel, data, q).collisions) {
      hitsParticle = hitsParticle || pair.second == "particle" || pair.first == "particle";
    }
  }
  EXPECT_TRUE(hitsParticle);
  // The detour: TCP at least h above... every waypoint at distance >= h from O, and motions valid
  // at the motion validator's resolution too.
  const Eigen::Vector3d o = thesisLinePoint(-0.1);
  for (const auto& pose : tcpPoses(arcplan::collision::waypointsOf(problem.setup->getSolutionPath()))) {
    EXPECT_GE((pose.translation() - o).norm(), 0.1 - 1e-9);
    EXPECT_LE(arcplan::robot::rotationDistance(pose.linear(), thesisToolDown()), 1e-6);
  }
  EXPECT_TRUE(problem.setup->getSolutionPath().check());
}

TEST(ArcPlanner, CheckMotionsValidatesEveryMotion) {
  auto problem = thesisProblem("thesis_obstacle");
  const auto [planner, status] = solve(problem, "arc", {{"sagitta", "0.1"}, {"check_motions", "1"}});
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  EXPECT_TRUE(arcOf(planner).getCheckMotions());
  // Every motion between consecutive waypoints is collision-free: certified by the motion check,
  // and no collision at a fine discrete sampling (1e-3 rad) written here.
  arcplan::collision::CollisionData data(*problem.collisionModel);
  const auto joints = arcplan::collision::waypointsOf(problem.setup->getSolutionPath());
  ASSERT_GT(joints.size(), 50u);  // 1 cm waypoints
  for (std::size_t i = 1; i < joints.size(); ++i) {
    EXPECT_TRUE(arcplan::collision::isMotionCollisionFree(*problem.collisionModel, data, joints[i - 1], joints[i]));
    const int samples = static_cast<int>(std::ceil((joints[i] - joints[i - 1]).cwiseAbs().maxCoeff() / 1e-3)) + 1;
    for (int k = 0; k <= samples; ++k) {
      const arcplan::robot::Vector6 q = joints[i - 1] + (joints[i] - joints[i - 1]) * (double(k) / samples);
      ASSERT_TRUE(arcplan::collision::isCollisionFree(*problem.collisionModel, data, q)) << "motion " << i;
    }
  }
}

TEST(ArcPlanner, HonoursTheTerminationCondition) {
  auto problem = thesisProblem("thesis_obstacle");
  auto planner = arcplan::planners::makePlanner("arc", problem.setup->getSpaceInformation(), problem.plannerContext());
  problem.setup->setPlanner(planner);
  problem.setup->setup();
  const auto status = planner->solve(ob::plannerAlwaysTerminatingCondition());
  EXPECT_EQ(status, ob::PlannerStatus::TIMEOUT);
  EXPECT_FALSE(problem.setup->getProblemDefinition()->hasSolution());
  EXPECT_NE(arcOf(planner).lastResult().reason.find("time limit"), std::string::npos);
}

TEST(ArcPlanner, PlannerDataReportsItsSolveTimeAndArcParameters) {
  auto problem = thesisProblem("thesis_obstacle");
  const auto [planner, status] = solve(problem, "arc", {{"sagitta", "0.15"}});
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION);
  ob::PlannerData data(problem.setup->getSpaceInformation());
  planner->getPlannerData(data);
  EXPECT_EQ(data.numVertices(), problem.setup->getSolutionPath().getStateCount());
  EXPECT_EQ(data.numEdges(), data.numVertices() - 1);
  EXPECT_EQ(data.numStartVertices(), 1u);
  EXPECT_EQ(data.numGoalVertices(), 1u);
  EXPECT_DOUBLE_EQ(std::stod(data.properties.at("arc sagitta REAL")), 0.15);
  EXPECT_DOUBLE_EQ(std::stod(data.properties.at("arc half chord REAL")), 0.2);
  EXPECT_EQ(data.properties.at("arc detours INTEGER"), "1");
  const double solveTime = std::stod(data.properties.at("solve time REAL"));
  EXPECT_GT(solveTime, 0.0);
  EXPECT_LE(solveTime, problem.setup->getLastPlanComputationTime());
  for (const auto& [name, value] : data.properties) {
    for (const char c : name) EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) || c == ' ') << name;
  }
}

TEST(ArcPlanner, RunsInOmplBenchmarkNextToRRTConnect) {
  auto problem = thesisProblem("thesis_obstacle");
  ompl::tools::Benchmark benchmark(*problem.setup, "arc_vs_rrtconnect");
  benchmark.addPlanner(arcplan::planners::makePlanner("arc", problem.setup->getSpaceInformation(),
                                                      problem.plannerContext(), {{"sagitta", "0.1"}}));
  benchmark.addPlanner(
      arcplan::planners::makePlanner("RRTConnect", problem.setup->getSpaceInformation(), problem.plannerContext()));
  ompl::tools::Benchmark::Request request(2.0, 1024.0, 2, 0.05, false, false, false);
  benchmark.benchmark(request);
  const auto& experiment = benchmark.getRecordedExperimentData();
  ASSERT_EQ(experiment.planners.size(), 2u);
  EXPECT_EQ(experiment.planners[0].name, "geometric_arc");
  EXPECT_EQ(experiment.planners[0].common.at("sagitta"), "0.1");
  EXPECT_EQ(experiment.planners[0].common.at("auto"), "0");
  for (const auto& planner : experiment.planners) {
    ASSERT_EQ(planner.runs.size(), 2u) << planner.name;
    for (const auto& run : planner.runs) EXPECT_EQ(run.at("solved BOOLEAN"), "1") << planner.name;
  }
  const auto& arcRun = experiment.planners[0].runs[0];
  EXPECT_DOUBLE_EQ(std::stod(arcRun.at("arc sagitta REAL")), 0.1);
  EXPECT_EQ(arcRun.at("correct solution BOOLEAN"), "1");
  EXPECT_GT(std::stod(arcRun.at("solve time REAL")), 0.0);
}

TEST(ArcPlanner, DetourThatDoesNotFitIsReported) {
  auto problem = thesisProblem("thesis_obstacle");
  // bx2 = r = 0.35 m for h = r with small side arcs > |AO| = 0.312 m.
  const auto [planner, status] =
      solve(problem, "arc", {{"sagitta", "0.35"}, {"half_chord", "0.35"}, {"entry_radius", "0.01"}});
  EXPECT_EQ(status, ob::PlannerStatus::ABORT);
  const std::string& reason = arcOf(planner).lastResult().reason;
  EXPECT_NE(reason.find("particle"), std::string::npos) << reason;
  EXPECT_NE(reason.find("|AO|"), std::string::npos) << reason;
  EXPECT_FALSE(problem.setup->haveSolutionPath());
}

TEST(ArcPlanner, LineThroughTheUnreachableCoreIsReported) {
  // From one side of the base to the other: the line passes the shoulder axis, where no IK exists.
  auto scene = std::make_shared<arcplan::collision::Scene>(*loadTestScene("thesis_free"));
  scene->queries[0].start = {std::array<double, 6>{0.35, -0.35, 0.3, 0.0, -M_PI, M_PI_2}, std::nullopt, std::nullopt};
  scene->queries[0].goal = {std::array<double, 6>{-0.35, 0.35, 0.3, 0.0, -M_PI, M_PI_2}, std::nullopt, std::nullopt};
  auto problem = arcplan::planners::makePlanningProblem(scene);
  const auto [planner, status] = solve(problem, "arc", {{"auto", "0"}});
  EXPECT_EQ(status, ob::PlannerStatus::ABORT);
  const std::string& reason = arcOf(planner).lastResult().reason;
  EXPECT_NE(reason.find("unreachable on the straight line"), std::string::npos) << reason;
  EXPECT_NE(reason.find("out of reach"), std::string::npos) << reason;
}

TEST(ArcPlanner, CollisionOnTheDetourNamesThePair) {
  // A block beside O, where a detour in the plane turned by +90 degrees passes.
  const Eigen::Vector3d direction = (thesisB() - thesisA()).normalized();
  const Eigen::Vector3d side = arcplan::planners::avoidanceDirection(direction, M_PI_2);
  auto problem = freeSceneWith({sphere("particle", thesisLinePoint(-0.1), 0.01),
                                box("side_block", thesisLinePoint(-0.1) + 0.15 * side, {0.04, 0.04, 0.04})});
  const auto [planner, status] = solve(problem, "arc", {{"sagitta", "0.15"}, {"plane_angle", std::to_string(M_PI_2)}});
  EXPECT_EQ(status, ob::PlannerStatus::ABORT);
  const std::string& reason = arcOf(planner).lastResult().reason;
  // The detour comes closer than the 1 cm clearance before it would collide.
  EXPECT_NE(reason.find("closer than the 0.01 m clearance"), std::string::npos) << reason;
  EXPECT_NE(reason.find("on arc detour 1"), std::string::npos) << reason;
  EXPECT_NE(reason.find("side_block"), std::string::npos) << reason;
}

TEST(ArcPlanner, ChainsDetoursAroundSeveralObstacles) {
  auto problem =
      freeSceneWith({sphere("first", thesisLinePoint(-0.2), 0.01), sphere("second", thesisLinePoint(0.2), 0.01)});
  const auto [planner, status] = solve(
      problem, "arc", {{"sagitta", "0.08"}, {"half_chord", "0.1"}, {"entry_radius", "0.05"}, {"exit_radius", "0.05"}});
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  const auto& result = arcOf(planner).lastResult();
  EXPECT_EQ(result.obstacles, (std::vector<std::string>{"first", "second"}));
  ASSERT_EQ(result.detours.size(), 2u);
  const double length = (thesisB() - thesisA()).norm();
  EXPECT_NEAR(result.detours[0].position, 0.25 * length, 1e-12);
  EXPECT_NEAR(result.detours[1].position, 0.75 * length, 1e-12);
  EXPECT_TRUE(problem.setup->getSolutionPath().check());
}

TEST(ArcPlanner, SolidObstacleIsAvoidedAroundItsBoundingBall) {
  // A 4 cm cube 1 cm beside the line: O is the line point nearest its centre.
  const Eigen::Vector3d center = thesisLinePoint(0.0) + Eigen::Vector3d(0.01, 0.0, 0.0);
  auto problem = freeSceneWith({box("cube", center, {0.04, 0.04, 0.04})});
  const auto [planner, status] = solve(problem, "arc", {{"sagitta", "0.15"}});
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  const auto& result = arcOf(planner).lastResult();
  ASSERT_EQ(result.detours.size(), 1u);
  const Eigen::Vector3d direction = (thesisB() - thesisA()).normalized();
  EXPECT_NEAR(result.detours[0].position, (center - thesisA()).dot(direction), 1e-12);
  EXPECT_TRUE(problem.setup->getSolutionPath().check());
}

TEST(ArcPlanner, AutoFindsAShorterValidPathThanTheThesisShapes) {
  auto problem = thesisProblem("thesis_obstacle");
  const auto [planner, status] = solve(problem, "arc");
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  EXPECT_TRUE(arcOf(planner).getAuto());
  const auto& result = arcOf(planner).lastResult();
  EXPECT_EQ(result.kind, ArcPlannerResult::Kind::ViaPoints);
  EXPECT_EQ(result.mode(), "arc");
  EXPECT_EQ(result.cartesianFraction, 1.0);
  ASSERT_FALSE(result.viaPoints.empty());
  // The straight line failed first, and at least one route before the one returned (the certifier of a
  // failed route must not leak into the next one: that used to reject valid routes or throw).
  EXPECT_GE(result.routesTried, 2);
  // Shorter than the shortest thesis case (h = 0.5 r: 0.8825 m) and longer than the straight line.
  EXPECT_LT(result.tcpPathLength, 0.8825);
  EXPECT_GT(result.tcpPathLength, (thesisB() - thesisA()).norm());
  EXPECT_TRUE(problem.setup->getSolutionPath().check());
  EXPECT_GE(closestApproach(problem), 0.01 - 1e-6);
}

TEST(ArcPlanner, TallPillarIsPassedSideways) {
  // A 1.6 m pillar across the line: its circumscribed ball (0.8 m) would forbid every detour, a
  // sideways one of a few decimetres clears it.
  arcplan::collision::Obstacle pillar;
  pillar.name = "pillar";
  pillar.shape = arcplan::collision::Obstacle::Shape::Cylinder;
  pillar.radius = 0.05;
  pillar.length = 1.6;
  const Eigen::Vector3d middle = thesisLinePoint(0.0);
  pillar.pose.translation() = Eigen::Vector3d(middle.x(), middle.y(), 0.8);
  auto problem = freeSceneWith({pillar});
  const auto [planner, status] = solve(problem, "arc");
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  EXPECT_EQ(arcOf(planner).lastResult().mode(), "arc");
  EXPECT_TRUE(problem.setup->getSolutionPath().check());
  for (const auto& pose : tcpPoses(arcplan::collision::waypointsOf(problem.setup->getSolutionPath()))) {
    EXPECT_GE((pose.translation() - pillar.pose.translation()).head<2>().norm(), 0.05 + 0.01);
  }
  EXPECT_GE(closestApproach(problem), 0.01 - 1e-6);
}

TEST(ArcPlanner, SeveralObstaclesOnTheLineArePassedInOneRoute) {
  auto problem =
      freeSceneWith({sphere("first", thesisLinePoint(-0.2), 0.02), sphere("second", thesisLinePoint(0.0), 0.02),
                     box("third", thesisLinePoint(0.2), {0.05, 0.05, 0.05})});
  const auto [planner, status] = solve(problem, "arc");
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  const auto& result = arcOf(planner).lastResult();
  EXPECT_EQ(result.mode(), "arc");
  EXPECT_FALSE(result.obstacles.empty());
  EXPECT_TRUE(problem.setup->getSolutionPath().check());
  EXPECT_GE(closestApproach(problem), 0.01 - 1e-6);
}

TEST(ArcPlanner, StartFiveMillimetresFromAnObstacleKeepsItsOwnClearance) {
  // A ball beside the flange at A, moved until the robot at A is 5 mm from it (measured).
  const auto start = thesisProblem("thesis_free").start;
  const Eigen::Vector3d tool = tcpPoses({start})[0].translation();
  const Eigen::Vector3d away = Eigen::Vector3d(1, -1, 0).normalized();  // outward, away from the base
  double low = 0.0, high = 0.3;
  auto scene = *loadTestScene("thesis_free");
  for (int k = 0; k < 40; ++k) {
    const double offset = 0.5 * (low + high);
    scene.obstacles.push_back(sphere("close", tool + offset * away, 0.02));
    const auto model = arcplan::collision::makeCollisionModel(scene);
    arcplan::collision::CollisionData data(*model);
    (arcplan::collision::distance(*model, data, start).obstacleDistance < 0.005 ? low : high) = offset;
    scene.obstacles.pop_back();
  }
  auto problem = freeSceneWith({sphere("close", tool + high * away, 0.02)});
  arcplan::collision::CollisionData data(*problem.collisionModel);
  ASSERT_NEAR(arcplan::collision::distance(*problem.collisionModel, data, start).obstacleDistance, 0.005, 1e-4);
  const auto [planner, status] = solve(problem, "arc");
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  EXPECT_EQ(arcOf(planner).lastResult().mode(), "arc");
  EXPECT_GE(closestApproach(problem), 0.005 - 1e-4);
}

TEST(ArcPlanner, GoalOnAnotherBranchGoesToTheFallbackOrIsReported) {
  auto scene = std::make_shared<arcplan::collision::Scene>(*loadTestScene("thesis_free"));
  auto problem = arcplan::planners::makePlanningProblem(scene);
  const arcplan::robot::UrInverseKinematics ik(arcplan::robot::ur10e());
  // The goal pose with the wrist flipped: same TCP pose, another branch; no TCP path joins them.
  arcplan::robot::Vector6 flipped = problem.goal;
  for (const auto& candidate : ik.solveAll(tcpPoses({problem.goal})[0])) {
    if (ik.branchOf(candidate) == (ik.branchOf(problem.goal) ^ 2)) flipped = candidate;
  }
  ASSERT_NE(ik.branchOf(flipped), ik.branchOf(problem.goal));
  scene->queries[0].goal = arcplan::collision::QueryEndpoint{std::nullopt, std::nullopt, flipped};
  auto flippedProblem = arcplan::planners::makePlanningProblem(scene);
  // RRTConnect finds no way to turn the wrist round within the time either (joint limits and the
  // table): the fallback was tried and says so.
  const auto [planner, status] = solve(flippedProblem, "arc", {}, 0.5);
  EXPECT_EQ(status, ob::PlannerStatus::TIMEOUT);
  const std::string& reason = arcOf(planner).lastResult().reason;
  EXPECT_NE(reason.find("branch change"), std::string::npos) << reason;
  // The goal was made by flipping the wrist bit (^ 2): the reason names that part and its singularity.
  EXPECT_NE(reason.find("differ in the wrist (only through the singularity q5 = 0"), std::string::npos) << reason;
  EXPECT_NE(reason.find("the joint-space fallback found no path"), std::string::npos) << reason;
  EXPECT_EQ(arcOf(planner).lastResult().mode(), "");
  const auto [strict, strictStatus] = solve(flippedProblem, "arc", {{"fallback", "0"}});
  EXPECT_EQ(strictStatus, ob::PlannerStatus::ABORT);
  EXPECT_NE(arcOf(strict).lastResult().reason.find("branch"), std::string::npos) << arcOf(strict).lastResult().reason;
}

TEST(ArcPlanner, ParameterSettersRejectOutOfRangeValues) {
  auto problem = thesisProblem("thesis_free");
  auto planner = arcplan::planners::makePlanner("arc", problem.setup->getSpaceInformation(), problem.plannerContext());
  EXPECT_THROW(arcplan::planners::setPlannerParameters(*planner, {{"resolution", "0"}}), arcplan::Error);
  EXPECT_THROW(arcplan::planners::setPlannerParameters(*planner, {{"half_chord", "-0.1"}}), arcplan::Error);
  EXPECT_THROW(arcplan::planners::setPlannerParameters(*planner, {{"plane_angle", "nan"}}), arcplan::Error);
  auto& arc = dynamic_cast<arcplan::planners::ArcPlanner&>(*planner);
  EXPECT_THROW(arcplan::planners::setPlannerParameters(*planner, {{"sagitta", "0"}}), arcplan::Error);
  EXPECT_TRUE(arc.getAuto());  // no detour shape given yet
  arc.setSagitta(0.1);
  EXPECT_FALSE(arc.getAuto());
  arc.setAuto(true);
  EXPECT_TRUE(arc.getAuto());
}

TEST(ArcPlanner, AutoPathKeepsTheRequestedClearance) {
  for (const double clearance : {0.01, 0.03}) {
    auto problem = thesisProblem("thesis_obstacle");
    const auto [planner, status] = solve(problem, "arc", {{"clearance", std::to_string(clearance)}});
    ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
    const double closest = closestApproach(problem);
    EXPECT_GE(closest, clearance - 1e-6) << "clearance " << clearance;
    // The shortest route keeping it: not far more (a larger clearance costs path length).
    EXPECT_LT(closest, clearance + 0.05) << "clearance " << clearance;
  }
}

// The shelf of planner_test_support.h: the tool must go round its side, and dozens of candidate
// routes fail at the same panel edge.
TEST(ArcPlanner, ShelfIsPassedWithTheClearanceOnASmoothPath) {
  auto problem = shelfProblem();
  const auto [planner, status] = solve(problem, "arc");
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << arcOf(planner).lastResult().reason;
  const ArcPlannerResult& result = arcOf(planner).lastResult();
  EXPECT_EQ(result.mode(), "arc");
  EXPECT_FALSE(result.viaPoints.empty());
  EXPECT_GE(closestApproach(problem), 0.01 - 1e-6);
  // C¹: the blended path through the reported via points has one position and one tangent at every
  // junction, and every waypoint lies on it (forward kinematics), the tool held down.
  const auto poses = tcpPoses(arcplan::collision::waypointsOf(problem.setup->getSolutionPath()));
  const arcplan::planners::BlendedPath path(poses.front(), poses.back(), result.viaPoints, result.blends);
  const auto& pieces = path.pieces();
  for (std::size_t k = 1; k < pieces.size(); ++k) {
    const auto& before = pieces[k - 1];
    EXPECT_LT((before.point(before.length) - pieces[k].point(0.0)).norm(), 1e-9) << "junction " << k;
    EXPECT_LT((before.tangent(before.length) - pieces[k].tangent(0.0)).norm(), 1e-9) << "junction " << k;
  }
  ASSERT_EQ(result.waypointArcLengths.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_LT((poses[i].translation() - path.position(result.waypointArcLengths[i])).norm(), 1e-6) << "waypoint " << i;
    EXPECT_LE(arcplan::robot::rotationDistance(poses[i].linear(), poses.front().linear()), 1e-6) << "waypoint " << i;
  }
  EXPECT_NEAR(result.tcpPathLength, path.length(), 1e-12);
}

}  // namespace
