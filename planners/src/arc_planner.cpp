#include "arcplan/planners/arc_planner.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/util/Console.h>

#include <ompl/base/ScopedState.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

#include "arc_planning.h"
#include "arcplan/collision/joint_states.h"
#include "arcplan/collision/ompl_validity.h"
#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace arcplan::planners {
namespace {

// Declared ranges (OMPL's "low:step:high"); the setters enforce the same bounds.
struct Range {
  double low, high;
  const char* suggestion;
};
const std::map<std::string, Range>& ranges() {
  static const std::map<std::string, Range> table = {
      {"sagitta", {0.001, 1.0, "0.001:0.01:1."}},
      {"half_chord", {0.001, 1.0, "0.001:0.01:1."}},
      {"entry_radius", {0.001, 1.0, "0.001:0.005:1."}},
      {"exit_radius", {0.001, 1.0, "0.001:0.005:1."}},
      {"plane_angle", {-M_PI, M_PI, "-3.14159:0.1:3.14159"}},
      {"resolution", {0.001, 0.1, "0.001:0.001:0.1"}},
      {"max_joint_step", {0.001, 0.5, "0.001:0.001:0.5"}},
      {"clearance", {0.0, 0.2, "0.:0.005:0.2"}},
  };
  return table;
}

std::string number(double value) {
  std::ostringstream text;
  text.precision(10);
  text << value;
  return text.str();
}

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
      ik_(collisionModel_->robot()) {
  specs_.approximateSolutions = false;
  specs_.optimizingPaths = false;
  specs_.multithreaded = false;
  specs_.directed = true;
  const auto& range = ranges();
  declareParam<double>("sagitta", this, &ArcPlanner::setSagitta, &ArcPlanner::getSagitta,
                       range.at("sagitta").suggestion);
  declareParam<double>("half_chord", this, &ArcPlanner::setHalfChord, &ArcPlanner::getHalfChord,
                       range.at("half_chord").suggestion);
  declareParam<double>("entry_radius", this, &ArcPlanner::setEntryRadius, &ArcPlanner::getEntryRadius,
                       range.at("entry_radius").suggestion);
  declareParam<double>("exit_radius", this, &ArcPlanner::setExitRadius, &ArcPlanner::getExitRadius,
                       range.at("exit_radius").suggestion);
  declareParam<double>("plane_angle", this, &ArcPlanner::setPlaneAngle, &ArcPlanner::getPlaneAngle,
                       range.at("plane_angle").suggestion);
  declareParam<double>("resolution", this, &ArcPlanner::setResolution, &ArcPlanner::getResolution,
                       range.at("resolution").suggestion);
  declareParam<double>("max_joint_step", this, &ArcPlanner::setMaxJointStep, &ArcPlanner::getMaxJointStep,
                       range.at("max_joint_step").suggestion);
  declareParam<bool>("check_motions", this, &ArcPlanner::setCheckMotions, &ArcPlanner::getCheckMotions, "0,1");
  declareParam<double>("clearance", this, &ArcPlanner::setClearance, &ArcPlanner::getClearance,
                       range.at("clearance").suggestion);
  declareParam<bool>("auto", this, &ArcPlanner::setAuto, &ArcPlanner::getAuto, "0,1");
  declareParam<bool>("fallback", this, &ArcPlanner::setFallback, &ArcPlanner::getFallback, "0,1");
  declareParam<unsigned int>("seed", this, &ArcPlanner::setSeed, &ArcPlanner::getSeed, "0:1:4294967295");
}

ArcPlanner::~ArcPlanner() = default;

double ArcPlanner::checkedParameter(const std::string& name, double value) const {
  const Range& range = ranges().at(name);
  if (!std::isfinite(value) || value < range.low || value > range.high) {
    std::ostringstream message;
    message << "arc planner parameter " << name << " must be a number in [" << range.low << ", " << range.high
            << "], got " << value;
    throw Error(message.str());
  }
  return value;
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

ob::PlannerStatus ArcPlanner::fail(ob::PlannerStatus status, const std::string& reason) {
  result_.kind = ArcPlannerResult::Kind::Failed;
  result_.reason = reason;
  OMPL_INFORM("%s: no path: %s", getName().c_str(), reason.c_str());
  return status;
}

ob::PlannerStatus ArcPlanner::solve(const ob::PlannerTerminationCondition& ptc) {
  const auto clockStart = std::chrono::steady_clock::now();
  checkValidity();
  result_ = ArcPlannerResult{};
  solution_.reset();
  solutionJoints_.clear();
  struct Timer {
    ArcPlannerResult& result;
    std::chrono::steady_clock::time_point start;
    ~Timer() { result.solveTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); }
  } timer{result_, clockStart};

  const ob::State* startState = pis_.nextStart();
  if (startState == nullptr) {
    return fail(ob::PlannerStatus::INVALID_START,
                "no valid start state (it is missing, outside the joint limits or in collision)");
  }
  if (dynamic_cast<const ob::GoalSampleableRegion*>(pdef_->getGoal().get()) == nullptr) {
    return fail(ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE,
                "the goal must be a goal state (or a sampleable goal region)");
  }
  const ob::State* goalState = pis_.nextGoal(ptc);
  if (goalState == nullptr) {
    return fail(ob::PlannerStatus::INVALID_GOAL,
                "no valid goal state (it is outside the joint limits or in collision)");
  }
  const robot::Vector6 start(collision::jointsOf(startState, 6)), goal(collision::jointsOf(goalState, 6));
  // The margin: the planner's clearance or the motion validator's, the larger; lowered to what a start
  // or goal closer to an obstacle has itself (else nothing could leave it).
  const auto* motionValidator = dynamic_cast<const collision::JointMotionValidator*>(si_->getMotionValidator().get());
  double margin = std::max(clearance_, motionValidator != nullptr ? motionValidator->options().minimumClearance
                                                                  : collision::MotionCheckOptions{}.minimumClearance);
  collision::CollisionData data(*collisionModel_);
  for (const robot::Vector6& end : {start, goal})
    margin = std::min(margin, collision::distance(*collisionModel_, data, end).minimum());
  const bool autoMode = getAuto();
  ob::ScopedState<> scratch(si_);
  const auto waypointValid = [&](const robot::Vector6& q) {
    collision::setJoints(scratch.get(), q);
    return si_->isValid(scratch.get());
  };
  // The auto mode's routes pass close to obstacles: their motions are always certified.
  PathValidator validator(*collisionModel_, ik_, conversion_, margin, checkMotions_ || autoMode, waypointValid,
                          [&ptc] { return ptc(); });
  const robot::RobotModel& robot = collisionModel_->robot();
  const detail::ArcQuery query{*collisionModel_,
                               obstacles_,
                               ik_,
                               conversion_,
                               ptc,
                               validator,
                               start,
                               goal,
                               robot::tipPose(robot, start),
                               robot::tipPose(robot, goal)};
  JointWaypoints path;
  if (ik_.branchOf(start) != ik_.branchOf(goal)) {
    // No TCP path joins two IK branches without passing a singularity: only the fallback can help.
    std::ostringstream message;
    message << "branch change: start and goal are on different IK branches: "
            << describeBranchChange(ik_.branchOf(start), ik_.branchOf(goal))
            << "; a TCP path keeps its branch (choose a goal seed on the start's branch)";
    result_.reason = message.str();
  } else {
    path = autoMode ? detail::planViaPoints(query, result_)
                    : detail::planThesisDetours(query, shape_, planeAngle_, result_);
  }
  if (path.joints.empty() && autoMode && fallback_ && !ptc()) {
    // Its own SpaceInformation, whose states and motions keep this planner's margin (the problem's
    // may be smaller).
    const auto fallbackSpace = collision::makeSpaceInformation(
        collisionModel_, motionValidator != nullptr ? motionValidator->options() : collision::MotionCheckOptions{},
        margin);
    path = detail::planInJointSpace(query, fallbackSpace, seed_, result_);
  }
  if (path.joints.empty()) return fail(ptc() ? ob::PlannerStatus::TIMEOUT : ob::PlannerStatus::ABORT, result_.reason);
  if (result_.kind != ArcPlannerResult::Kind::Fallback) result_.cartesianFraction = 1.0;
  result_.reason.clear();
  setSolution(path);
  return ob::PlannerStatus::EXACT_SOLUTION;
}

void ArcPlanner::setSolution(const JointWaypoints& waypoints) {
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
  data.properties["solve time REAL"] = number(result_.solveTime);
  data.properties["arc mode ENUM"] = mode == "arc" ? "1" : mode == "fallback" ? "2" : "0";
  data.properties["cartesian fraction REAL"] = number(result_.cartesianFraction);
  data.properties["arc via points INTEGER"] = std::to_string(result_.viaPoints.size());
  data.properties["arc routes INTEGER"] = std::to_string(result_.routesTried);
  data.properties["arc detours INTEGER"] = std::to_string(result_.detours.size());
  data.properties["arc analytic length REAL"] = number(result_.tcpPathLength);
  const Detour first =
      result_.detours.empty() ? Detour{0.0, ArcParameters{0.0, 0.0, 0.0, 0.0}, 0.0} : result_.detours[0];
  data.properties["arc sagitta REAL"] = number(first.shape.sagitta);
  data.properties["arc half chord REAL"] = number(first.shape.halfChord);
  data.properties["arc entry radius REAL"] = number(first.shape.entryRadius);
  data.properties["arc exit radius REAL"] = number(first.shape.exitRadius);
  data.properties["arc plane angle REAL"] = number(first.planeAngle);
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
