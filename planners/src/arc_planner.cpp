#include "arcplan/planners/arc_planner.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/util/Console.h>

#include <ompl/base/ScopedState.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "arc_planning.h"
#include "arcplan/collision/joint_states.h"
#include "arcplan/collision/ompl_validity.h"
#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/trajectory/time_scaling.h"
#include "planner_properties.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace arcplan::planners {
namespace {

// The real-valued parameters: declared ranges (OMPL's "low:step:high"), which the setters enforce.
struct RealParameter {
  const char* name;
  double low, high;
  const char* suggestion;
  void (ArcPlanner::*set)(double);
  double (ArcPlanner::*get)() const;
};
const std::vector<RealParameter>& realParameters() {
  using P = ArcPlanner;
  static const std::vector<RealParameter> table = {
      {"sagitta", 0.001, 1.0, "0.001:0.01:1.", &P::setSagitta, &P::getSagitta},
      {"half_chord", 0.001, 1.0, "0.001:0.01:1.", &P::setHalfChord, &P::getHalfChord},
      {"entry_radius", 0.001, 1.0, "0.001:0.005:1.", &P::setEntryRadius, &P::getEntryRadius},
      {"exit_radius", 0.001, 1.0, "0.001:0.005:1.", &P::setExitRadius, &P::getExitRadius},
      {"plane_angle", -M_PI, M_PI, "-3.14159:0.1:3.14159", &P::setPlaneAngle, &P::getPlaneAngle},
      {"resolution", 0.001, 0.1, "0.001:0.001:0.1", &P::setResolution, &P::getResolution},
      {"max_joint_step", 0.001, 0.5, "0.001:0.001:0.5", &P::setMaxJointStep, &P::getMaxJointStep},
      {"clearance", 0.0, 0.2, "0.:0.005:0.2", &P::setClearance, &P::getClearance},
      {"deadline", 0.0, 60.0, "0.:0.01:60.", &P::setDeadline, &P::getDeadline},
      {"speed_limit", 0.01, 2.0, "0.01:0.01:2.", &P::setSpeedLimit, &P::getSpeedLimit},
      {"fallback_range", 0.0, 100.0, "0.:0.1:100.", &P::setFallbackRange, &P::getFallbackRange},
      {"fallback_plans", 1.0, 8.0, "1.:1.:8.", &P::setFallbackPlans, &P::getFallbackPlans},
      {"fallback_threads", 1.0, 8.0, "1.:1.:8.", &P::setFallbackThreads, &P::getFallbackThreads},
  };
  return table;
}

using detail::propertyNumber;

}  // namespace

std::string ArcPlannerResult::mode() const {
  if (kind == Kind::Fallback) return "fallback";
  return kind == Kind::None || kind == Kind::Failed ? "" : "arc";
}

ArcPlanner::ArcPlanner(const ob::SpaceInformationPtr& si,
                       std::shared_ptr<const collision::CollisionModel> collisionModel,
                       std::vector<collision::Obstacle> obstacles)
    : ob::Planner(si, "arc"),
      collisionModel_(std::move(collisionModel)),
      obstacles_(std::move(obstacles)),
      ik_(collisionModel_->robot()),
      linkOutlines_(linkOutlines(collisionModel_->robot())) {
  specs_.approximateSolutions = false;
  specs_.optimizingPaths = false;
  specs_.multithreaded = false;
  specs_.directed = true;
  for (const RealParameter& parameter : realParameters())
    declareParam<double>(parameter.name, this, parameter.set, parameter.get, parameter.suggestion);
  declareParam<bool>("check_motions", this, &ArcPlanner::setCheckMotions, &ArcPlanner::getCheckMotions, "0,1");
  declareParam<bool>("auto", this, &ArcPlanner::setAuto, &ArcPlanner::getAuto, "0,1");
  declareParam<bool>("fallback", this, &ArcPlanner::setFallback, &ArcPlanner::getFallback, "0,1");
  declareParam<unsigned int>("seed", this, &ArcPlanner::setSeed, &ArcPlanner::getSeed, "0:1:4294967295");
}

ArcPlanner::~ArcPlanner() = default;

double ArcPlanner::checkedParameter(const std::string& name, double value) const {
  const RealParameter& range = *std::find_if(realParameters().begin(), realParameters().end(),
                                             [&](const RealParameter& parameter) { return parameter.name == name; });
  if (!std::isfinite(value) || value < range.low || value > range.high) {
    std::ostringstream message;
    message << "arc planner parameter " << name << " must be a number in [" << range.low << ", " << range.high
            << "], got " << value;
    throw Error(message.str());
  }
  return value;
}

int ArcPlanner::checkedCount(const std::string& name, double value, const std::string& what) const {
  if (checkedParameter(name, value) != std::round(value)) {
    throw Error("arc planner parameter " + name + " must be a whole number of " + what + ", got " +
                propertyNumber(value));
  }
  return static_cast<int>(value);
}

void ArcPlanner::setSagitta(double sagitta) {
  shape_.sagitta = checkedParameter("sagitta", sagitta);
  shapeGiven_ = true;
}
void ArcPlanner::setHalfChord(double halfChord) { shape_.halfChord = checkedParameter("half_chord", halfChord); }
void ArcPlanner::setEntryRadius(double radius) { shape_.entryRadius = checkedParameter("entry_radius", radius); }
void ArcPlanner::setExitRadius(double radius) { shape_.exitRadius = checkedParameter("exit_radius", radius); }
void ArcPlanner::setPlaneAngle(double angle) { planeAngle_ = checkedParameter("plane_angle", angle); }
void ArcPlanner::setResolution(double resolution) {
  conversion_.resolution = checkedParameter("resolution", resolution);
}
void ArcPlanner::setMaxJointStep(double step) { conversion_.maxJointStep = checkedParameter("max_joint_step", step); }
void ArcPlanner::setClearance(double clearance) { clearance_ = checkedParameter("clearance", clearance); }
void ArcPlanner::setDeadline(double seconds) { deadline_ = checkedParameter("deadline", seconds); }
void ArcPlanner::setSpeedLimit(double speed) { speedLimit_ = checkedParameter("speed_limit", speed); }
void ArcPlanner::setFallbackRange(double range) { fallbackRange_ = checkedParameter("fallback_range", range); }
void ArcPlanner::setFallbackPlans(double plans) { fallbackPlans_ = checkedCount("fallback_plans", plans, "plans"); }
void ArcPlanner::setFallbackThreads(double threads) {
  fallbackThreads_ = checkedCount("fallback_threads", threads, "threads");
  specs_.multithreaded = fallbackThreads_ > 1;
}

void ArcPlanner::clear() {
  Planner::clear();
  result_ = ArcPlannerResult{};
  solution_.reset();
  solutionJoints_.clear();
}

void ArcPlanner::setup() {
  Planner::setup();
  if (si_->getStateDimension() != static_cast<unsigned int>(collisionModel_->robot().dof())) {
    OMPL_ERROR("%s: the state space has %u dimensions, the robot %d joints", getName().c_str(),
               si_->getStateDimension(), collisionModel_->robot().dof());
    setup_ = false;
  }
}

ob::PlannerStatus ArcPlanner::solve(const ob::PlannerTerminationCondition& ptc) {
  const auto clockStart = std::chrono::steady_clock::now();
  checkValidity();
  result_ = ArcPlannerResult{};
  solution_.reset();
  solutionJoints_.clear();
  const ob::State* startState = pis_.nextStart();
  if (startState == nullptr) {
    return finish(detail::failure("no valid start state (it is missing, outside the joint limits or in collision)"),
                  ob::PlannerStatus::INVALID_START, clockStart);
  }
  if (dynamic_cast<const ob::GoalSampleableRegion*>(pdef_->getGoal().get()) == nullptr) {
    return finish(detail::failure("the goal must be a goal state (or a sampleable goal region)"),
                  ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE, clockStart);
  }
  const ob::State* goalState = pis_.nextGoal(ptc);
  if (goalState == nullptr) {
    return finish(detail::failure("no valid goal state (it is outside the joint limits or in collision)"),
                  ob::PlannerStatus::INVALID_GOAL, clockStart);
  }
  detail::ArcOutcome outcome = answer(ptc, collision::jointsOf(startState, 6), collision::jointsOf(goalState, 6));
  const ob::PlannerStatus status = outcome.solved() ? ob::PlannerStatus::EXACT_SOLUTION
                                   : ptc()          ? ob::PlannerStatus::TIMEOUT
                                                    : ob::PlannerStatus::ABORT;
  return finish(std::move(outcome), status, clockStart);
}

detail::ArcOutcome ArcPlanner::answer(const ob::PlannerTerminationCondition& ptc, const robot::Vector6& start,
                                      const robot::Vector6& goal) {
  const collision::MotionCheckOptions motionCheck = motionCheckOptions();
  const collision::EndpointClearance required = requiredClearance(motionCheck, start, goal);
  // The search's own deadline: past it the search gives up (a fence-like cell can keep it busy for
  // seconds), leaving the rest of the caller's time to the fallback.
  const ob::PlannerTerminationCondition searchEnds =
      deadline_ > 0.0 ? ob::plannerOrTerminationCondition(ptc, ob::timedPlannerTerminationCondition(deadline_)) : ptc;
  detail::ArcOutcome outcome = withQuery(searchEnds, required, start, goal, [&](const detail::ArcQuery& query) {
    if (ik_.branchOf(start) != ik_.branchOf(goal)) {
      // No TCP path joins two IK branches without passing a singularity: only the fallback can help.
      return detail::failure("branch change: start and goal are on different IK branches: " +
                             describeBranchChange(ik_.branchOf(start), ik_.branchOf(goal)) +
                             "; a TCP path keeps its branch (choose a goal seed on the start's branch)");
    }
    return getAuto() ? detail::planViaPoints(query) : detail::planThesisDetours(query, shape_, planeAngle_);
  });
  const std::string timeLimit = "time limit reached";
  if (!outcome.solved() && outcome.reason.rfind(timeLimit, 0) == 0 && !ptc()) {
    std::ostringstream deadline;
    deadline << "deadline of " << deadline_ * 1000.0 << " ms reached";
    outcome.reason.replace(0, timeLimit.size(), deadline.str());
  }
  if (outcome.solved() || !getAuto() || !fallback_ || ptc()) return outcome;
  detail::ArcOutcome fallback = withQuery(ptc, required, start, goal, [&](const detail::ArcQuery& query) {
    trajectory::TimeScalingOptions options;
    options.maxTcpSpeed = speedLimit_;
    const robot::RobotModel& robot = collisionModel_->robot();
    const detail::ExecutionTiming timing{
        [&](const std::vector<robot::Vector6>& joints) { return trajectory::scaledDuration(robot, joints, options); },
        [&](const std::vector<robot::Vector6>& joints) { return trajectory::plannedDuration(robot, joints, options); }};
    return detail::planInJointSpace(query, fallbackSpace(motionCheck, required, start, goal),
                                    {seed_, fallbackRange_, static_cast<std::uint_fast32_t>(fallbackPlans_),
                                     static_cast<std::uint_fast32_t>(fallbackThreads_)},
                                    timing);
  });
  // What the search met stays part of the answer; its reason leads a failure's.
  fallback.obstacles = std::move(outcome.obstacles);
  fallback.routesTried = outcome.routesTried;
  fallback.reason = outcome.reason + "; " + fallback.reason;
  return fallback;
}

detail::ArcOutcome ArcPlanner::withQuery(const ob::PlannerTerminationCondition& ptc,
                                         const collision::EndpointClearance& required, const robot::Vector6& start,
                                         const robot::Vector6& goal,
                                         const std::function<detail::ArcOutcome(const detail::ArcQuery&)>& strategy) {
  ob::ScopedState<> scratch(si_);
  const auto waypointValid = [&](const robot::Vector6& q) {
    collision::setJoints(scratch.get(), q);
    return si_->isValid(scratch.get());
  };
  // Asked at every waypoint a walk or screen meets: the termination condition (with the deadline two clock reads, 3 %
  // of a quick query) is evaluated every kStopStride-th time, a few microseconds of walking apart; once true it stays.
  constexpr int kStopStride = 8;
  int asked = 0;
  bool stopped = false;
  const auto stopRequested = [&ptc, &asked, &stopped] {
    if (!stopped && asked++ % kStopStride == 0) stopped = ptc();
    return stopped;
  };
  // The auto mode's routes pass close to obstacles: their motions are always certified.
  PathValidator validator(*collisionModel_, ik_, conversion_, required, checkMotions_ || getAuto(), waypointValid,
                          stopRequested);
  const robot::RobotModel& robot = collisionModel_->robot();
  const detail::ArcQuery query{*collisionModel_,
                               obstacles_,
                               linkOutlines_,
                               ik_,
                               conversion_,
                               ptc,
                               validator,
                               start,
                               goal,
                               robot::tipPose(robot, start),
                               robot::tipPose(robot, goal),
                               ik_.branchOf(start)};
  return strategy(query);
}

collision::MotionCheckOptions ArcPlanner::motionCheckOptions() const {
  const auto* validator = dynamic_cast<const collision::JointMotionValidator*>(si_->getMotionValidator().get());
  return validator != nullptr ? validator->options() : collision::MotionCheckOptions{};
}

collision::EndpointClearance ArcPlanner::requiredClearance(const collision::MotionCheckOptions& motionCheck,
                                                           const robot::Vector6& start,
                                                           const robot::Vector6& goal) const {
  const double margin = std::max(clearance_, motionCheck.minimumClearance);
  return collision::EndpointClearance(*collisionModel_, margin, margin,
                                      {robot::JointVector(start), robot::JointVector(goal)});
}

ob::SpaceInformationPtr ArcPlanner::fallbackSpace(const collision::MotionCheckOptions& motionCheck,
                                                  const collision::EndpointClearance& required,
                                                  const robot::Vector6& start, const robot::Vector6& goal) const {
  const auto* checker =
      dynamic_cast<const collision::CollisionStateValidityChecker*>(si_->getStateValidityChecker().get());
  if (checker != nullptr) {
    const collision::EndpointClearance& problem = checker->requiredClearance();
    const auto sameZone = [](const collision::ApproachZone& a, const collision::ApproachZone& b) {
      return a.endpoint == b.endpoint && a.stateClearance == b.stateClearance && a.motionClearance == b.motionClearance;
    };
    if (problem.clearance() == required.clearance() && problem.motionClearance() == required.motionClearance() &&
        std::equal(problem.zones().begin(), problem.zones().end(), required.zones().begin(), required.zones().end(),
                   sameZone)) {
      return si_;
    }
  }
  return collision::makeSpaceInformation(collisionModel_, motionCheck, required.clearance(),
                                         {robot::JointVector(start), robot::JointVector(goal)});
}

ob::PlannerStatus ArcPlanner::finish(detail::ArcOutcome outcome, ob::PlannerStatus status,
                                     std::chrono::steady_clock::time_point clockStart) {
  result_.kind = outcome.kind;
  result_.reason = std::move(outcome.reason);
  result_.detours = std::move(outcome.detours);
  result_.obstacles = std::move(outcome.obstacles);
  result_.viaPoints = std::move(outcome.viaPoints);
  result_.blends = std::move(outcome.blends);
  result_.tcpPathLength = outcome.tcpPathLength;
  result_.cartesianFraction = outcome.cartesianFraction;
  result_.routesTried = outcome.routesTried;
  result_.fallbackTimes = outcome.fallbackTimes;
  result_.simplificationTime = outcome.simplificationTime;
  if (outcome.solved()) {
    setSolution(outcome.path);
  } else {
    OMPL_INFORM("%s: no path: %s", getName().c_str(), result_.reason.c_str());
  }
  const double wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - clockStart).count();
  result_.solveTime = wallTime - result_.simplificationTime;
  return status;
}

void ArcPlanner::setSolution(const JointConversionResult& waypoints) {
  result_.waypointArcLengths = waypoints.arcLengths;
  solutionJoints_ = waypoints.joints;
  // The problem definition gets its own path: simplifying it must not change what this planner
  // reports (getPlannerData builds its states from solutionJoints_).
  auto path = std::make_shared<og::PathGeometric>(si_);
  ob::State* state = si_->allocState();
  for (const robot::Vector6& q : waypoints.joints) {
    collision::setJoints(state, q);
    path->append(state);
  }
  si_->freeState(state);
  pdef_->addSolutionPath(path, false, 0.0, getName());
}

void ArcPlanner::getPlannerData(ob::PlannerData& data) const {
  Planner::getPlannerData(data);
  const std::string mode = result_.mode();
  detail::recordSolveTime(data, result_.solveTime);
  // OMPL's Benchmark records RRTConnect's simplification under this name; this planner's is its fallback's
  // first plan's, 0 where there was none.
  data.properties["simplification time REAL"] = propertyNumber(result_.simplificationTime);
  data.properties["arc mode ENUM"] = mode == "arc" ? "1" : mode == "fallback" ? "2" : "0";
  data.properties["cartesian fraction REAL"] = propertyNumber(result_.cartesianFraction);
  data.properties["arc via points INTEGER"] = std::to_string(result_.viaPoints.size());
  data.properties["arc routes INTEGER"] = std::to_string(result_.routesTried);
  data.properties["arc detours INTEGER"] = std::to_string(result_.detours.size());
  data.properties["arc analytic length REAL"] = propertyNumber(result_.tcpPathLength);
  const Detour first =
      result_.detours.empty() ? Detour{0.0, ArcParameters{0.0, 0.0, 0.0, 0.0}, 0.0} : result_.detours[0];
  data.properties["arc sagitta REAL"] = propertyNumber(first.shape.sagitta);
  data.properties["arc half chord REAL"] = propertyNumber(first.shape.halfChord);
  data.properties["arc entry radius REAL"] = propertyNumber(first.shape.entryRadius);
  data.properties["arc exit radius REAL"] = propertyNumber(first.shape.exitRadius);
  data.properties["arc plane angle REAL"] = propertyNumber(first.planeAngle);
  if (solutionJoints_.empty()) return;
  // Built on request only: PlannerData refers to states the planner owns.
  if (!solution_) {
    solution_ = std::make_shared<og::PathGeometric>(si_);
    ob::State* state = si_->allocState();
    for (const robot::Vector6& q : solutionJoints_) {
      collision::setJoints(state, q);
      solution_->append(state);
    }
    si_->freeState(state);
  }
  const std::vector<ob::State*>& states = solution_->getStates();
  for (std::size_t i = 0; i < states.size(); ++i) {
    const ob::PlannerDataVertex vertex(states[i]);
    if (i == 0) {
      data.addStartVertex(vertex);
    } else if (i + 1 == states.size()) {
      data.addGoalVertex(vertex);
    } else {
      data.addVertex(vertex);
    }
    if (i > 0) data.addEdge(data.vertexIndex(states[i - 1]), data.vertexIndex(states[i]));
  }
}

}  // namespace arcplan::planners
