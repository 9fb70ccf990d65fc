#pragma once
// The arcplan half of the side-by-side benchmark (perf/peer_vamp_mbm.cpp): MoveIt problems as VAMP
// shapes, arcplan's planners run as `arcplan plan` runs them, and the exact check every path gets.
#include <Eigen/Geometry>

#include <string>
#include <utility>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/planners/planning_problem.h"
#include "vamp_side.h"

namespace arcplan::peer_vamp {

// The obstacles of a MoveIt problem as VAMP's MBM loader (problem_dict_to_vamp) makes them, in the
// URDF root frame: a box is a cuboid, a sphere a sphere, and a cylinder a capsule (the cylinder
// with a half ball on each end: VAMP has no cylinder test) — except in MBM's "box" scenes, where
// VAMP takes the box around the cylinder instead (the grasp there is from above). Both contain
// the cylinder. Throws arcplan::Error for a mesh or an attached body, which VAMP's loader has not.
VampScene toVampScene(const collision::MoveItProblem& problem, bool cylindersAsCuboids);

// VAMP's rule for which problems get boxes around cylinders: its problem name "box" (our family
// folder box_ur5).
bool cylindersAsCuboids(const std::string& family);

struct PlannerRun {
  bool solved = false;
  std::string reason;  // why not, when not solved
  std::vector<Joints> path;
  double planningUs = 0.0;        // the planner's own solve time (what `arcplan plan` reports)
  double simplificationUs = 0.0;  // OMPL's simplifier (0 for arc, whose path is kept as planned)
  double totalUs = 0.0;           // steady_clock around solve and simplification
  std::string mode;               // arc planner: "arc", "line", "joint" ... as it reports it
};

// One planner by registry name on the problem with the given parameters, as `arcplan plan` runs it:
// SimpleSetup::solve within `timeLimit` seconds, then OMPL's simplifier when benchmarks::simplifiesSolution says so,
// its result kept only where every motion is certified (planners::simplifySolutionKeepingCertified). Only an exact
// solution counts as solved. The problem keeps no clearance beyond contact, as VAMP plans: nor does the arc planner
// (benchmarks::keepProblemClearance; until 2026-11-25 it kept its own 1 cm here, a harder problem than the others').
PlannerRun runArcplanPlanner(planners::PlanningProblem& problem, const std::string& plannerName,
                             const std::vector<std::pair<std::string, std::string>>& parameters, double timeLimit);

// arcplan's planner parameters beside VAMP's settings: RRTConnect extends by VAMP's RRT range, and the arc
// planner's fallback runs that same RRTConnect (as the mbm-ur5 suite configures them).
std::vector<std::pair<std::string, std::string>> sameRangeAsVamp(const std::string& plannerName);

// The exact verdict on a path: every motion between consecutive waypoints certified free under the
// meshes (collision::isMotionCollisionFree, MotionCheck::Certified at `minimumClearance`), and how
// far its ends are from the requested start and goal (largest joint difference, rad); and what certifying it cost with
// arcplan's certified check, whoever planned the path.
struct PathCheck {
  bool valid = false;
  std::string firstFailure;  // "motion 3 of 7" when not valid
  double startError = 0.0;
  double goalError = 0.0;
  // µs, stopwatch around the certified checks of a valid path, from a fresh workspace (none remembered); 0 when not
  // valid
  double certificationUs = 0.0;
};
PathCheck checkPathExactly(const collision::CollisionModel& model, const std::vector<Joints>& path, const Joints& start,
                           const Joints& goal, double minimumClearance);

// Largest distance between VAMP's end-effector frame and arcplan's FK of the same link at q, both
// in the URDF root frame: position [m] and rotation angle [rad].
struct FrameDifference {
  double position = 0.0;
  double rotation = 0.0;
};
FrameDifference endEffectorDifference(const robot::RobotModel& model, const Eigen::Isometry3d& baseInRoot,
                                      const std::string& link, const Joints& q);

// Joint-space length of a path (sum of Euclidean distances between waypoints) [rad]: VAMP's path cost.
double pathLength(const std::vector<Joints>& path);

}  // namespace arcplan::peer_vamp
