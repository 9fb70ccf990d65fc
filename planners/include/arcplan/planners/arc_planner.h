#pragma once
// The thesis' arc obstacle-avoidance planner as an OMPL planner (DESIGN.md §4): it solves the same
// joint-space problems as RRTConnect & co. and is used the same way (SimpleSetup::setPlanner,
// ompl::tools::Benchmark::addPlanner).
//
// solve(): forward kinematics of the start and goal states give the TCP poses A and B. Obstacles that
// block the straight TCP line (a LIN move) for the whole robot are found: at the line point nearest
// each obstacle (one IK + one collision check each), and by walking the path. Each is replaced by the
// point O on the line nearest its bounding-ball centre (a particle: that point; a solid: the thesis'
// circumscribed ball) and gets an arc detour (arc_path.h); with none the answer is the straight
// line. The TCP path is converted to joints on the start's IK branch (cartesian_to_joint.h) and
// validated with the SpaceInformation: every motion between consecutive waypoints (checkMotion: with
// arcplan's certified motion validator no configuration along it collides), or with check_motions = 0
// only the waypoints themselves (isValid; waypoints at most `resolution` apart along the TCP path and
// `max_joint_step` apart in every joint, like MoveIt's Cartesian paths).
//
// Parameters (declareParam: they appear in benchmark logs and are set by name):
//   sagitta         h (m); 0 = not given. With auto: the smallest sagitta searched
//   half_chord      r (m), default 0.2 (thesis)
//   entry_radius    R2 (m), default 0.1 (thesis 0.5·r)
//   exit_radius     R3 (m), default 0.2 (thesis r)
//   plane_angle     rotation of the avoidance plane about A→B from "up" (rad), default 0
//   resolution      largest TCP arc length between waypoints (m), default 0.01
//   max_joint_step  largest joint change between waypoints (rad), default 0.05
//   check_motions   validate every motion (1, default) or only the waypoints (0)
//   clearance       with check_motions: the smallest distance (m) every configuration of the path
//                   keeps from obstacles and between links, default 0.01 (the motion validator's
//                   own margin if larger); the auto search returns the shortest detour keeping it
//   auto            search h, r, R2, R3 and the plane angle for the shortest detour valid for the
//                   whole robot (default: on while no sagitta is given, off once one is); a path
//                   with a searched detour has every motion validated, since the shortest detours
//                   pass close to the obstacle
// Without auto, exactly (h, r, R2, R3, plane_angle) is used for every blocking obstacle.
// Failures say why (lastResult().reason; also OMPL_INFORM): unreachable pose, joint limits, branch
// change, collision (with the colliding pairs), no detour fits between A and B, time limit. The
// status is then ABORT (TIMEOUT when the termination condition stopped it).
#include <ompl/base/Planner.h>
#include <ompl/geometric/PathGeometric.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/planners/arc_path.h"
#include "arcplan/planners/cartesian_to_joint.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::planners {

// Outcome of the last solve(), for users and for the command line.
struct ArcPlannerResult {
  enum class Kind {
    None,          // solve() not called since the last clear()
    StraightLine,  // the LIN move was valid
    Detour,        // line with arc detours
    Failed,
  };
  Kind kind = Kind::None;
  std::string reason;                      // why it failed; empty otherwise
  std::vector<Detour> detours;             // of the returned path
  std::vector<std::string> obstacles;      // blocking obstacles, in order along the line
  double solveTime = 0.0;                  // s, this planner's own solve time
  double tcpPathLength = 0.0;              // m, analytic length of the returned TCP path
  int candidatesTried = 0;                 // detour shapes checked (auto search)
  std::vector<double> waypointArcLengths;  // TCP arc length of each state of the solution path
};

class ArcPlanner : public ompl::base::Planner {
 public:
  // `collisionModel` names the bodies behind a failed motion and `obstacles` (the scene's) give their
  // bounding balls; both must describe the robot and scene of the SpaceInformation's validity checker.
  ArcPlanner(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const collision::CollisionModel> collisionModel,
             const std::vector<collision::Obstacle>& obstacles);
  ~ArcPlanner() override;

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  void setup() override;
  void getPlannerData(ompl::base::PlannerData& data) const override;

  const ArcPlannerResult& lastResult() const { return result_; }

  // Setters throw arcplan::Error for values outside their range (lengths and steps > 0, sagitta >= 0).
  void setSagitta(double sagitta);
  double getSagitta() const { return shape_.sagitta; }
  void setHalfChord(double halfChord);
  double getHalfChord() const { return shape_.halfChord; }
  void setEntryRadius(double radius);
  double getEntryRadius() const { return shape_.entryRadius; }
  void setExitRadius(double radius);
  double getExitRadius() const { return shape_.exitRadius; }
  void setPlaneAngle(double angle);
  double getPlaneAngle() const { return planeAngle_; }
  void setResolution(double resolution);
  double getResolution() const { return conversion_.resolution; }
  void setMaxJointStep(double step);
  double getMaxJointStep() const { return conversion_.maxJointStep; }
  void setCheckMotions(bool enabled) { checkMotions_ = enabled; }
  bool getCheckMotions() const { return checkMotions_; }
  void setClearance(double clearance);
  double getClearance() const { return clearance_; }
  void setAuto(bool enabled) { autoSearch_ = enabled; }
  // Explicit setting, else on while no sagitta is given.
  bool getAuto() const { return autoSearch_.value_or(shape_.sagitta <= 0.0); }

 private:
  struct Search;
  struct Blockage;
  struct ObstacleBall {
    std::string name;
    Eigen::Vector3d center;
    double radius = 0.0;
  };
  ompl::base::PlannerStatus fail(ompl::base::PlannerStatus status, const std::string& reason);
  // The obstacle blocks the line at distance u from A, in configuration `joints` (colliding `report`).
  Blockage blockage(Search& search, const ArcPath& line, const ObstacleBall& obstacle, double u,
                    const robot::Vector6& joints, const collision::CollisionReport& report);
  // The given shape, or (auto) the shortest valid one of the search.
  std::optional<Detour> chooseDetour(Search& search, const std::vector<Detour>& chosen, const Blockage& blocked,
                                     std::string& failure);

  std::shared_ptr<const collision::CollisionModel> collisionModel_;
  std::vector<ObstacleBall> obstacles_;
  robot::UrInverseKinematics ik_;
  ArcParameters shape_{0.0, 0.2, 0.1, 0.2};  // thesis r, R2 = 0.5 r, R3 = r; no sagitta
  double planeAngle_ = 0.0;
  std::optional<bool> autoSearch_;
  // 1 cm between waypoints: the joint path then follows the arcs to a fraction of a millimetre and
  // its time scaling has no speed dips at the waypoints (5 cm reproduces the thesis' measured, shorter
  // polyline lengths of Table 3.3, at the price of TCP chords of up to 3 mm on the entry arc).
  JointConversionOptions conversion_{0.01, 0.05, 6};
  bool checkMotions_ = true;
  // A detour that grazes the obstacle is valid but useless next to people: 1 cm by default.
  double clearance_ = 0.01;
  ArcPlannerResult result_;
  std::vector<robot::Vector6> solutionJoints_;  // the last solution's waypoints
  mutable std::shared_ptr<ompl::geometric::PathGeometric> solution_;  // owns the states getPlannerData reports
};

}  // namespace arcplan::planners
