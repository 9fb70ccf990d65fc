#pragma once
// The arc planner as an OMPL planner (geometry and contract in docs/planners.md): it solves the same
// joint-space problems as RRTConnect & co. and is used the same way (SimpleSetup::setPlanner,
// ompl::tools::Benchmark::addPlanner). Forward kinematics of the start and goal states give the TCP
// poses A and B; the answer is a TCP path of straight lines and circular arcs (tool orientation held,
// or slerped when A and B differ), converted to joints on the start's IK branch and validated for
// the whole robot while it is converted (path_validation.h).
//
// Two modes, chosen by the parameter `auto`:
//   - thesis (auto = 0): the straight line A→B, every obstacle that blocks it replaced by the
//     thesis' three-arc detour with exactly the given h, r, R2, R3 and plane angle (arc_path.h);
//   - auto (default): lines through via points with blended corners (blended_path.h), the via points
//     from the obstacles' geometry (via_points.h), the fastest route found by a lazy search
//     (route_search.h); where no such route exists, the joint-space fallback: RRTConnect on the
//     problem's SpaceInformation (one keeping the planner's margin if that is larger), its random
//     draws from `seed` as a benchmark run's RRTConnect draws from the run seed (seeded_sampling.h),
//     simplified as `plan` and `bench` simplify RRTConnect's path, then shortcut for the TCP where that pays
//     (up to 4 plans, the fastest kept); then of that path, its segments as straight TCP lines where
//     they validate, and mixes of the two, the one that executes fastest at `speed_limit` (reason
//     says which). lastResult().mode says which
//     ("arc" or "fallback"), cartesianFraction how much of the TCP path is lines and arcs.
// A path keeps `clearance` (or the motion validator's margin if larger) everywhere, except in the
// approach zone of a start or goal closer than that to an obstacle (collision/endpoint_clearance.h:
// the rule the problem's validity checker and motion validator apply).
// The line-and-arc search has its own `deadline` (default 50 ms of wall-clock time): past it, it gives
// up and the fallback gets the rest of the termination condition's time (without fallback the planner
// fails at once, its reason naming the deadline).
// Failures say why (lastResult().reason; also OMPL_INFORM); the status is then ABORT, TIMEOUT when
// the termination condition stopped it.
#include <ompl/base/Planner.h>
#include <ompl/geometric/PathGeometric.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/endpoint_clearance.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/planners/arc_path.h"
#include "arcplan/planners/cartesian_to_joint.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::planners {
namespace detail {
// planners/src/arc_planning.h: one query, and what one way of answering it found.
struct ArcQuery;
struct ArcOutcome;
}  // namespace detail

// Outcome of the last solve(), for users and for the command line.
struct ArcPlannerResult {
  enum class Kind {
    None,          // solve() not called since the last clear()
    StraightLine,  // the LIN move was valid
    Detour,        // thesis mode: the line with three-arc detours
    ViaPoints,     // auto: lines through via points with blended corners
    Fallback,      // auto: the joint-space fallback
    Failed,
  };
  Kind kind = Kind::None;
  std::string reason;                      // why it failed; for the fallback why the line search gave up; else empty
  std::vector<Detour> detours;             // thesis mode: of the returned path
  std::vector<std::string> obstacles;      // bodies that blocked a line or leg, in the order met
  std::vector<Eigen::Vector3d> viaPoints;  // auto: of the returned path
  std::vector<double> blends;              // auto: tangent length of each via point's blend (m)
  // s, this planner's own solve time, without simplificationTime (as OMPL's Benchmark times RRTConnect's
  // solve apart from its simplification)
  double solveTime = 0.0;
  // s, fallback: the first plan's simplification (and the check of its result), run to the end even past
  // the time limit (docs/planners.md, "Fallback")
  double simplificationTime = 0.0;
  double tcpPathLength = 0.0;      // m, analytic length of the line-and-arc part
  double cartesianFraction = 0.0;  // share of the TCP path's length that is lines and arcs
  int routesTried = 0;             // auto: routes walked
  // Fallback: execution times (s) at speed_limit of RRTConnect's simplified joint path, of its segments
  // as TCP lines where they validate (the fallback before it compared), and of the path kept — the
  // fastest of those two and their mixes; reason says which was kept. firstPlan: the plan drawn from
  // `seed` itself as RRTConnect + simplifier gave it, what a campaign run with that run seed gives plain
  // RRTConnect + simplifier (kept is never slower, provided that plan's RRTConnect found its path within
  // the time limit; its simplification runs to the end: docs/planners.md, "Fallback").
  struct FallbackTimes {
    double jointPath = 0.0, linePath = 0.0, kept = 0.0, firstPlan = 0.0;
  } fallbackTimes;
  std::vector<double> waypointArcLengths;  // TCP arc length of each state of the solution path

  // "arc" for a line-and-arc path, "fallback" for the joint-space fallback, "" without a path.
  std::string mode() const;
};

class ArcPlanner : public ompl::base::Planner {
public:
  // `collisionModel` names the bodies behind a failed motion and `obstacles` (the scene's) give the
  // via points and detour positions; both must describe the robot and scene of the SpaceInformation's
  // validity checker.
  ArcPlanner(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const collision::CollisionModel> collisionModel,
             std::vector<collision::Obstacle> obstacles);
  ~ArcPlanner() override;

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  void setup() override;
  // Vertices and edges of the solution, and the properties "solve time REAL", "simplification time
  // REAL" (the fallback's first plan's: a benchmark run records it where it records RRTConnect's), "arc mode ENUM"
  // (0 none, 1 arc, 2 fallback), "cartesian fraction REAL", "arc via points INTEGER", "arc routes
  // INTEGER", "arc detours INTEGER", "arc analytic length REAL" and the first detour's shape.
  void getPlannerData(ompl::base::PlannerData& data) const override;

  const ArcPlannerResult& lastResult() const { return result_; }

  // Setters throw arcplan::Error for values outside the range their parameter declares.
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
  // Seconds the line-and-arc search may take (0: no deadline); past it the search gives up and the
  // fallback (if enabled) gets the rest of the termination condition's time. Wall-clock time: a run
  // that reaches it depends on the machine's speed, so runs that must repeat exactly set 0.
  void setDeadline(double seconds);
  // TCP speed limit (m/s) at which the fallback compares execution times (trajectory::scaleToTcpSpeed).
  void setSpeedLimit(double speed);
  double getSpeedLimit() const { return speedLimit_; }
  // The fallback's RRTConnect `range` (rad of joint-space distance; 0: RRTConnect's own default, 0.2 of the
  // joint space's extent). A suite that sets RRTConnect's range sets this to the same value, so that the
  // fallback's first plan stays what a plain RRTConnect run of the same seed computes.
  void setFallbackRange(double range);
  double getFallbackRange() const { return fallbackRange_; }
  // Joint-space plans (seeds seed, seed + 1, ...) the fallback draws and keeps the fastest of (1–8, default 4; later
  // plans only while the termination condition allows): fewer answer sooner, more execute faster. The first is
  // always the plan RRTConnect + simplifier of the same seed gives, so what is kept never executes slower than it.
  void setFallbackPlans(double plans);
  double getFallbackPlans() const { return fallbackPlans_; }
  // Threads that draw those plans at once (1–8, default 1): the same plans, taken in the same order, so the same
  // path; sooner on a machine with cores to spare, the same CPU time in all. One by default, as every other planner
  // a benchmark compares it with runs on one thread.
  void setFallbackThreads(double threads);
  double getFallbackThreads() const { return fallbackThreads_; }
  double getDeadline() const { return deadline_; }
  // Giving a detour shape (sagitta) asks for the thesis mode unless auto is set explicitly.
  void setAuto(bool enabled) { autoMode_ = enabled; }
  bool getAuto() const { return autoMode_.value_or(!shapeGiven_); }
  void setFallback(bool enabled) { fallback_ = enabled; }
  bool getFallback() const { return fallback_; }
  // Seeds every random draw of the fallback (its own generators, not OMPL's process-wide seed).
  void setSeed(unsigned int seed) { seed_ = seed; }
  unsigned int getSeed() const { return seed_; }

private:
  // One query answered by the mode's strategy and, in auto mode, the fallback after it.
  detail::ArcOutcome answer(const ompl::base::PlannerTerminationCondition& ptc, const robot::Vector6& start,
                            const robot::Vector6& goal);
  // Runs `strategy` on the query of start and goal, its walks validated by `required` and stopped by `ptc`.
  detail::ArcOutcome withQuery(const ompl::base::PlannerTerminationCondition& ptc,
                               const collision::EndpointClearance& required, const robot::Vector6& start,
                               const robot::Vector6& goal,
                               const std::function<detail::ArcOutcome(const detail::ArcQuery&)>& strategy);
  collision::MotionCheckOptions motionCheckOptions() const;
  // The planner's clearance or the motion validator's, the larger, with approach zones around a start
  // or goal closer than that (the one endpoint rule, collision/endpoint_clearance.h).
  collision::EndpointClearance requiredClearance(const collision::MotionCheckOptions& motionCheck,
                                                 const robot::Vector6& start, const robot::Vector6& goal) const;
  // The SpaceInformation the fallback plans on: the problem's own when it asks what `required` asks
  // (then the fallback's RRTConnect solves exactly the problem a plain RRTConnect solves), else one
  // with `required`'s clearances and zones.
  ompl::base::SpaceInformationPtr fallbackSpace(const collision::MotionCheckOptions& motionCheck,
                                                const collision::EndpointClearance& required,
                                                const robot::Vector6& start, const robot::Vector6& goal) const;
  // The outcome becomes lastResult() (and the solution path when there is one).
  ompl::base::PlannerStatus finish(detail::ArcOutcome outcome, ompl::base::PlannerStatus status,
                                   std::chrono::steady_clock::time_point clockStart);
  void setSolution(const JointConversionResult& waypoints);
  double checkedParameter(const std::string& name, double value) const;
  // checkedParameter for a count: also a whole number (`what` names its unit in the error).
  int checkedCount(const std::string& name, double value, const std::string& what) const;

  std::shared_ptr<const collision::CollisionModel> collisionModel_;
  std::vector<collision::Obstacle> obstacles_;
  robot::UrInverseKinematics ik_;
  // Per link, points outlining its collision geometry: where a link met a body (src/arm_contact.h).
  std::vector<std::vector<Eigen::Vector3d>> linkOutlines_;
  ArcParameters shape_{0.1, 0.2, 0.1, 0.2};  // the thesis example: h = 0.5 r, r = 0.2, R2 = 0.5 r, R3 = r
  bool shapeGiven_ = false;
  double planeAngle_ = 0.0;
  std::optional<bool> autoMode_;
  bool fallback_ = true;
  // 1 cm between waypoints: the joint path then follows the arcs to a fraction of a millimetre and
  // its time scaling has no speed dips at the waypoints (5 cm reproduces the thesis' measured, shorter
  // polyline lengths of Table 3.3, at the price of TCP chords of up to 3 mm on the entry arc).
  JointConversionOptions conversion_{0.01, 0.05, 6};
  bool checkMotions_ = true;
  // A path that grazes an obstacle is valid but useless next to people: 1 cm by default.
  double clearance_ = 0.01;
  // 50 ms: the search answers most queries in about 1 ms; one that has not found a route by then
  // rarely finds one later (issue 22: a fence kept it busy for 5 s).
  double deadline_ = 0.05;
  double speedLimit_ = 0.25;  // m/s: the collaborative limit of the thesis and the benchmark suites
  double fallbackRange_ = 0.0;
  int fallbackPlans_ = 4;
  int fallbackThreads_ = 1;
  ArcPlannerResult result_;
  std::vector<robot::Vector6> solutionJoints_;                        // the last solution's waypoints
  mutable std::shared_ptr<ompl::geometric::PathGeometric> solution_;  // owns the states getPlannerData reports
  unsigned int seed_ = 1;                                             // of the fallback's random draws
};

}  // namespace arcplan::planners
