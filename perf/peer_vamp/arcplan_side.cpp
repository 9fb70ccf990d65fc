#include "arcplan_side.h"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/geometric/SimpleSetup.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "arcplan/benchmarks/solution_policy.h"
#include "arcplan/collision/joint_states.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/common/error.h"
#include "arcplan/planners/arc_planner.h"
#include "arcplan/planners/certified_simplification.h"
#include "arcplan/planners/planner_registry.h"
#include "arcplan/robot/kinematics.h"

namespace arcplan::peer_vamp {
namespace {

Point point(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

VampCuboid cuboid(const Eigen::Isometry3d& pose, const Eigen::Vector3d& halfExtents) {
  VampCuboid box;
  box.center = point(pose.translation());
  for (int axis = 0; axis < 3; ++axis) box.axes[axis] = point(pose.linear().col(axis));
  box.halfExtents = point(halfExtents);
  return box;
}

Joints toJoints(const robot::Vector6& q) {
  Joints joints{};
  for (int j = 0; j < 6; ++j) joints[j] = q[j];
  return joints;
}

robot::Vector6 toVector(const Joints& q) { return Eigen::Map<const robot::Vector6>(q.data()); }

double largestDifference(const Joints& a, const Joints& b) {
  double largest = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) largest = std::max(largest, std::abs(a[j] - b[j]));
  return largest;
}

// What made a motion fail the certified check: the first state in contact after the last state the
// check certified, searched in steps of 1/2000 of the motion, with its colliding pairs; or none found
// (the motion came closer than the minimum clearance, or touched between the steps).
std::string describeFailure(const collision::CollisionModel& model, collision::CollisionData& data,
                            const robot::JointVector& from, const robot::JointVector& to, double lastValid) {
  constexpr int kSteps = 2000;
  for (int k = static_cast<int>(std::floor(lastValid * kSteps)); k <= kSteps; ++k) {
    const double s = static_cast<double>(k) / kSteps;
    const robot::JointVector q = from + s * (to - from);
    const collision::CollisionReport report = collision::collide(model, data, q);
    if (!report.valid) {
      std::ostringstream text;
      text << "in contact at " << std::setprecision(4) << s << " of the motion ("
           << collision::describeCollisions(report) << ")";
      return text.str();
    }
  }
  return "no contact found in 2000 steps (closer than the minimum clearance)";
}

}  // namespace

VampScene toVampScene(const collision::MoveItProblem& problem, bool cylindersAsCuboids) {
  if (!problem.scene.attachedObstacles.empty()) {
    throw Error("scene " + problem.scene.sourceFile.string() + ": attached bodies are not compared with VAMP");
  }
  VampScene scene;
  for (const collision::Obstacle& obstacle : problem.scene.obstacles) {
    const Eigen::Isometry3d pose = problem.baseInPlanningFrame * obstacle.pose;
    switch (obstacle.shape) {
      case collision::Obstacle::Shape::Box:
        scene.cuboids.push_back(cuboid(pose, obstacle.size / 2.0));
        break;
      case collision::Obstacle::Shape::Sphere:
        scene.spheres.push_back({point(pose.translation()), obstacle.radius});
        break;
      case collision::Obstacle::Shape::Cylinder:
        if (cylindersAsCuboids) {
          scene.cuboids.push_back(cuboid(pose, {obstacle.radius, obstacle.radius, obstacle.length / 2.0}));
        } else {
          const Eigen::Vector3d half = pose.linear().col(2) * (obstacle.length / 2.0);
          scene.capsules.push_back(
              {point(pose.translation() + half), point(pose.translation() - half), obstacle.radius});
        }
        break;
      case collision::Obstacle::Shape::Mesh:
        throw Error("scene " + problem.scene.sourceFile.string() + ": obstacle '" + obstacle.name +
                    "' is a mesh, which VAMP's MoveIt problems do not have");
    }
  }
  return scene;
}

bool cylindersAsCuboids(const std::string& family) { return family == "box" || family == "box_ur5"; }

std::vector<std::pair<std::string, std::string>> sameRangeAsVamp(const std::string& plannerName) {
  const std::string range = std::to_string(VampSettings{}.range);
  if (plannerName == "arc") return {{"fallback_range", range}};
  return {{"range", range}};
}

PlannerRun runArcplanPlanner(planners::PlanningProblem& problem, const std::string& plannerName,
                             const std::vector<std::pair<std::string, std::string>>& parameters, double timeLimit) {
  ompl::geometric::SimpleSetup& setup = *problem.setup;
  setup.clear();  // the previous planner's solution and data
  const ompl::base::PlannerPtr planner =
      planners::makePlanner(plannerName, setup.getSpaceInformation(), problem.plannerContext(), parameters);
  // No clearance beyond contact, as VAMP: the arc planner's own 1 cm too.
  benchmarks::keepProblemClearance(*planner, 0.0, false);
  setup.setPlanner(planner);
  setup.setup();

  const auto clock = std::chrono::steady_clock::now();
  // The deadline read by the planner itself: SimpleSetup::solve(t) from 1 s on evaluates it on a thread that sleeps in
  // 1 ms steps and is joined after the solve, up to ~1 ms that is neither planning nor VAMP's (planner_registry.h).
  setup.solve(ompl::base::timedPlannerTerminationCondition(timeLimit));
  const bool exact = setup.haveExactSolutionPath();
  if (exact && benchmarks::simplifiesSolution(plannerName)) planners::simplifySolutionKeepingCertified(setup);
  PlannerRun run;
  run.totalUs = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - clock).count();

  const auto* arc = dynamic_cast<const planners::ArcPlanner*>(planner.get());
  run.planningUs = 1e6 * planners::lastSolveTime(*planner);
  if (!exact) {
    run.reason = arc ? arc->lastResult().reason : "no exact path within " + std::to_string(timeLimit) + " s";
    return run;
  }
  run.solved = true;
  if (benchmarks::simplifiesSolution(plannerName)) run.simplificationUs = 1e6 * setup.getLastSimplificationTime();
  if (arc) run.mode = arc->lastResult().mode();
  for (const robot::Vector6& q : collision::waypointsOf(setup.getSolutionPath())) run.path.push_back(toJoints(q));
  return run;
}

PathCheck checkPathExactly(const collision::CollisionModel& model, const std::vector<Joints>& path, const Joints& start,
                           const Joints& goal, double minimumClearance) {
  PathCheck check;
  if (path.empty()) {
    check.firstFailure = "empty path";
    return check;
  }
  check.startError = largestDifference(path.front(), start);
  check.goalError = largestDifference(path.back(), goal);
  collision::CollisionData data(model);
  collision::MotionCheckOptions options;
  options.method = collision::MotionCheck::Certified;
  options.minimumClearance = minimumClearance;
  // A one-waypoint path is the motion from that state to itself: the state check.
  const std::size_t motions = std::max<std::size_t>(path.size() - 1, 1);
  const auto clockStart = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < motions; ++i) {
    const robot::JointVector from = toVector(path[i]);
    const robot::JointVector to = toVector(path[std::min(i + 1, path.size() - 1)]);
    // Checked as the planners' motion validators check (no last valid fraction asked: finding it searches the motion
    // from its start, 3.6 times the time on RRTConnect's MBM paths); a refused motion is searched again for it, to
    // describe the failure. Both checks are certificates: a motion either one accepts is certified.
    if (collision::isMotionCollisionFree(model, data, from, to, nullptr, options)) continue;
    double lastValid = 0.0;
    if (!collision::isMotionCollisionFree(model, data, from, to, &lastValid, options)) {
      check.firstFailure = "motion " + std::to_string(i + 1) + " of " + std::to_string(motions) + ": " +
                           describeFailure(model, data, from, to, lastValid);
      return check;
    }
  }
  check.certificationUs =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - clockStart).count();
  check.valid = true;
  return check;
}

FrameDifference endEffectorDifference(const robot::RobotModel& model, const Eigen::Isometry3d& baseInRoot,
                                      const std::string& link, const Joints& q) {
  robot::KinematicsData data(model);
  robot::forwardKinematics(model, toVector(q), data);
  const Eigen::Isometry3d ours = baseInRoot * data.linkPoses[model.linkIndex(link)];
  const std::array<double, 16> matrix = vampEndEffectorPose(q);
  Eigen::Isometry3d theirs;
  theirs.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(matrix.data());
  const Eigen::AngleAxisd rotation(ours.linear().transpose() * theirs.linear());
  return {(ours.translation() - theirs.translation()).norm(), std::abs(rotation.angle())};
}

double pathLength(const std::vector<Joints>& path) {
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) length += (toVector(path[i]) - toVector(path[i - 1])).norm();
  return length;
}

}  // namespace arcplan::peer_vamp
