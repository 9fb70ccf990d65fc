#include "arcplan/planners/arc_planner.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

#include "arcplan/collision/motion_check.h"
#include "arcplan/collision/ompl_validity.h"
#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace arcplan::planners {
namespace {

// Detour shapes the auto search tries around one obstacle (m, rad). Sagittas from a hair above the
// line to beyond the thesis' largest (0.2 m); half chords at least the sagitta (Table 3.1 needs
// h <= r); side radii as fractions of r (the thesis uses R2 = 0.5 r, R3 = r); planes every 30°.
const double kSearchSagittas[] = {0.02, 0.03, 0.04, 0.05, 0.06, 0.08, 0.10, 0.12, 0.15, 0.20, 0.25, 0.30};
const double kSearchChordRatios[] = {1.0, 1.5, 2.0, 3.0};
const double kSearchRadiusRatios[] = {0.5, 1.0};
constexpr int kSearchPlaneSteps = 12;
// At most this many detours are chained along one line.
constexpr int kMaxDetours = 8;
// Failed search candidates whose colliding pairs are named in the reason (naming costs a full query).
constexpr int kNamedCollisionFailures = 3;

std::string describeCollisions(const collision::CollisionReport& report) {
  std::string text;
  for (const auto& [first, second] : report.collisions) text += (text.empty() ? "" : ", ") + first + "–" + second;
  return text.empty() ? "between two waypoints" : text;
}

bool involves(const collision::CollisionReport& report, const std::string& body) {
  return std::any_of(report.collisions.begin(), report.collisions.end(),
                     [&](const collision::NamePair& pair) { return pair.first == body || pair.second == body; });
}

double checkedParameter(const char* name, double value, bool zeroAllowed) {
  if (!std::isfinite(value) || value < 0.0 || (value == 0.0 && !zeroAllowed)) {
    std::ostringstream message;
    message << "arc planner parameter " << name << " must be a finite number " << (zeroAllowed ? ">= 0" : "> 0")
            << ", got " << value;
    throw Error(message.str());
  }
  return value;
}

// Index of `detour` once inserted into `detours` (kept ascending along the line).
std::size_t insertSorted(std::vector<Detour>& detours, const Detour& detour) {
  const auto place = std::upper_bound(detours.begin(), detours.end(), detour.position,
                                      [](double position, const Detour& d) { return position < d.position; });
  const auto index = static_cast<std::size_t>(place - detours.begin());
  detours.insert(place, detour);
  return index;
}

}  // namespace

// Where an obstacle blocks the straight line: its O, and the stretch of the line (distance from A)
// on which the robot hits it.
struct ArcPlanner::Blockage {
  const ObstacleBall* obstacle = nullptr;
  double position = 0.0;        // O: the line point nearest the obstacle's bounding-ball centre
  double from = 0.0, to = 0.0;  // blocked stretch
  robot::Vector6 joints;        // a blocked configuration on the line (IK seed for detours)
  std::string pairs;            // the colliding pairs there
};

// State of one solve() call.
struct ArcPlanner::Search {
  Search(ArcPlanner& planner, const ob::PlannerTerminationCondition& ptc)
      : planner(planner),
        ptc(ptc),
        si(*planner.si_),
        model(*planner.collisionModel_),
        data(model),
        previousState(si.allocState()),
        state(si.allocState()) {}
  ~Search() {
    si.freeState(previousState);
    si.freeState(state);
  }
  Search(const Search&) = delete;
  Search& operator=(const Search&) = delete;

  ArcPlanner& planner;
  const ob::PlannerTerminationCondition& ptc;
  const ob::SpaceInformation& si;
  const collision::CollisionModel& model;
  collision::CollisionData data;
  ob::State* previousState;
  ob::State* state;
  Eigen::Isometry3d a, b;
  robot::Vector6 start, goal;
  // The last motion the walk rejected.
  robot::Vector6 rejectedPrevious, rejectedJoints;
  // Validate motions, not only waypoints: check_motions, or a detour from the auto search (the
  // shortest detours pass close to the obstacle).
  bool strict = false;
  std::optional<collision::PathCertifier> certifier;  // of the current walk, when strict
  double margin = 0.0;  // m, the clearance strict validation keeps: the planner's or the validator's, the larger

  void toState(const robot::Vector6& q, ob::State* target) const {
    for (int j = 0; j < 6; ++j) *si.getStateSpace()->getValueAddressAtIndex(target, j) = q[j];
  }

  robot::Vector6 toJoints(const ob::State* source) const {
    robot::Vector6 q;
    for (int j = 0; j < 6; ++j) q[j] = *si.getStateSpace()->getValueAddressAtIndex(source, j);
    return q;
  }

  // The verdict on the motion previous -> q: certified like the motion validator's (`strict`), or
  // the SpaceInformation's validity of q alone (waypoints a bounded joint step apart).
  bool validMotion(const robot::Vector6& previous, const robot::Vector6& q, bool strict) {
    if (!strict) {
      toState(q, state);
      return si.isValid(state);
    }
    // The path certifier validates each motion like JointMotionValidator's certified check, with
    // its minimum clearance, but reuses one waypoint's clearance for the next few waypoints.
    if (!certifier) {
      certifier.emplace(model, data, margin);
      if (!certifier->start(previous)) return false;
    }
    return certifier->extend(q);
  }

  // Continues the validated `prefix` (waypoints this path shares with the last one) to the goal and
  // stops at the first motion that fails. Returns prefix + continuation.
  JointWaypoints walk(const ArcPath& path, const JointWaypoints& prefix) {
    certifier.reset();  // a walk continues from the prefix's last waypoint
    const WaypointCheck check = [this](const robot::Vector6& previous, const robot::Vector6& q, double) {
      if (ptc()) return false;
      if (validMotion(previous, q, strict)) return true;
      rejectedPrevious = previous;
      rejectedJoints = q;
      return false;
    };
    JointWaypoints continuation =
        convertToJoints(planner.ik_, path, prefix.joints.back(), goal, planner.conversion_, prefix.arcLengths.back(),
                        std::numeric_limits<double>::infinity(), check);
    JointWaypoints combined = prefix;
    combined.joints.insert(combined.joints.end(), continuation.joints.begin() + 1, continuation.joints.end());
    combined.arcLengths.insert(combined.arcLengths.end(), continuation.arcLengths.begin() + 1,
                               continuation.arcLengths.end());
    combined.status = continuation.status;
    combined.reason = continuation.reason;
    combined.failedAtArcLength = continuation.failedAtArcLength;
    return combined;
  }

  // Why the rejected motion was rejected: the pairs colliding at its end state or along it; else
  // (no collision, but closer than the clearance) the closest pair along it.
  struct Rejection {
    collision::CollisionReport pairs;
    bool collides = true;
    double closest = 0.0;  // m, when it does not collide

    std::string describe(double clearance) const {
      std::ostringstream text;
      if (collides) {
        text << "collision (" << describeCollisions(pairs) << ")";
      } else {
        text << "closer than the " << clearance << " m clearance (" << describeCollisions(pairs) << " at " << closest
             << " m)";
      }
      return text.str();
    }
  };
  Rejection rejection() {
    const auto along = [&](int k) -> robot::Vector6 {
      return rejectedPrevious + (rejectedJoints - rejectedPrevious) * (k / 16.0);
    };
    Rejection result;
    result.pairs = collision::collide(model, data, rejectedJoints);
    for (int k = 1; k < 16 && result.pairs.valid; ++k) result.pairs = collision::collide(model, data, along(k));
    if (!result.pairs.valid) return result;
    result.collides = false;
    result.closest = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= 16; ++k) {
      const collision::DistanceReport d = collision::distance(model, data, along(k));
      const bool obstacleCloser = d.obstacleDistance <= d.selfDistance;
      if (d.minimum() < result.closest) {
        result.closest = d.minimum();
        result.pairs.collisions = {obstacleCloser ? d.obstaclePair : d.selfPair};
      }
    }
    return result;
  }
};

ArcPlanner::ArcPlanner(const ob::SpaceInformationPtr& si,
                       std::shared_ptr<const collision::CollisionModel> collisionModel,
                       const std::vector<collision::Obstacle>& obstacles)
    : ob::Planner(si, "arc"), collisionModel_(std::move(collisionModel)), ik_(collisionModel_->robot()) {
  for (const collision::Obstacle& obstacle : obstacles) {
    obstacles_.push_back({obstacle.name, obstacle.boundingCenter(), obstacle.boundingRadius()});
  }
  specs_.approximateSolutions = false;
  specs_.optimizingPaths = false;
  specs_.multithreaded = false;
  specs_.directed = true;
  declareParam<double>("sagitta", this, &ArcPlanner::setSagitta, &ArcPlanner::getSagitta, "0.:0.01:1.");
  declareParam<double>("half_chord", this, &ArcPlanner::setHalfChord, &ArcPlanner::getHalfChord, "0.01:0.01:1.");
  declareParam<double>("entry_radius", this, &ArcPlanner::setEntryRadius, &ArcPlanner::getEntryRadius,
                       "0.005:0.005:1.");
  declareParam<double>("exit_radius", this, &ArcPlanner::setExitRadius, &ArcPlanner::getExitRadius, "0.005:0.005:1.");
  declareParam<double>("plane_angle", this, &ArcPlanner::setPlaneAngle, &ArcPlanner::getPlaneAngle, "-3.14:0.1:3.14");
  declareParam<double>("resolution", this, &ArcPlanner::setResolution, &ArcPlanner::getResolution, "0.001:0.001:0.1");
  declareParam<double>("max_joint_step", this, &ArcPlanner::setMaxJointStep, &ArcPlanner::getMaxJointStep,
                       "0.001:0.001:0.5");
  declareParam<bool>("check_motions", this, &ArcPlanner::setCheckMotions, &ArcPlanner::getCheckMotions, "0,1");
  declareParam<double>("clearance", this, &ArcPlanner::setClearance, &ArcPlanner::getClearance, "0.:0.005:0.2");
  declareParam<bool>("auto", this, &ArcPlanner::setAuto, &ArcPlanner::getAuto, "0,1");
}

ArcPlanner::~ArcPlanner() = default;

void ArcPlanner::setClearance(double clearance) { clearance_ = checkedParameter("clearance", clearance, true); }
void ArcPlanner::setSagitta(double sagitta) { shape_.sagitta = checkedParameter("sagitta", sagitta, true); }
void ArcPlanner::setHalfChord(double halfChord) { shape_.halfChord = checkedParameter("half_chord", halfChord, false); }
void ArcPlanner::setEntryRadius(double radius) { shape_.entryRadius = checkedParameter("entry_radius", radius, false); }
void ArcPlanner::setExitRadius(double radius) { shape_.exitRadius = checkedParameter("exit_radius", radius, false); }
void ArcPlanner::setResolution(double resolution) {
  conversion_.resolution = checkedParameter("resolution", resolution, false);
}
void ArcPlanner::setMaxJointStep(double step) {
  conversion_.maxJointStep = checkedParameter("max_joint_step", step, false);
}
void ArcPlanner::setPlaneAngle(double angle) {
  if (!std::isfinite(angle)) throw Error("arc planner parameter plane_angle must be a finite number (rad)");
  planeAngle_ = angle;
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

  Search search(*this, ptc);
  search.strict = checkMotions_;
  const auto* validator = dynamic_cast<const collision::JointMotionValidator*>(si_->getMotionValidator().get());
  search.margin = std::max(clearance_, validator != nullptr ? validator->options().minimumClearance
                                                            : collision::MotionCheckOptions{}.minimumClearance);
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
  search.start = search.toJoints(startState);
  search.goal = search.toJoints(goalState);
  const robot::RobotModel& robotModel = collisionModel_->robot();
  search.a = robot::tipPose(robotModel, search.start);
  search.b = robot::tipPose(robotModel, search.goal);
  if (ik_.branchOf(search.start) != ik_.branchOf(search.goal)) {
    std::ostringstream message;
    message << "branch change: the start configuration is on IK branch " << ik_.branchOf(search.start)
            << ", the goal on branch " << ik_.branchOf(search.goal)
            << "; a TCP path keeps its branch (choose a goal seed on the start's branch)";
    return fail(ob::PlannerStatus::ABORT, message.str());
  }
  const ArcPath line(search.a, search.b);

  // Obstacles on the line (the thesis' situation) show up at the line point nearest them: one IK
  // and one collision check each, instead of walking the line up to the first collision.
  std::vector<Detour> detours;  // ascending along the line
  std::vector<Blockage> blockages;
  for (const ObstacleBall& obstacle : obstacles_) {
    const double u =
        std::clamp((obstacle.center - search.a.translation()).dot(line.lineDirection()), 0.0, line.straightLength());
    const double fraction = line.straightLength() > 0.0 ? u / line.straightLength() : 0.0;
    const robot::Vector6 seed = search.start + fraction * (search.goal - search.start);
    const std::optional<robot::Vector6> q = ik_.solveNearest(line.pose(u), seed);
    if (!q || ik_.branchOf(*q) != ik_.branchOf(search.start)) continue;  // the walk will tell
    if (collision::isCollisionFree(*collisionModel_, search.data, *q)) continue;
    const collision::CollisionReport report = collision::collide(*collisionModel_, search.data, *q);
    if (involves(report, obstacle.name)) blockages.push_back(blockage(search, line, obstacle, u, *q, report));
  }
  std::sort(blockages.begin(), blockages.end(),
            [](const Blockage& x, const Blockage& y) { return x.position < y.position; });
  for (const Blockage& blocked : blockages) {
    std::ostringstream context;
    context << "'" << blocked.obstacle->name << "' blocks the straight line at " << blocked.position << " m from A ("
            << blocked.pairs << ")";
    std::string failure;
    const std::optional<Detour> detour = chooseDetour(search, detours, blocked, failure);
    if (!detour)
      return fail(ptc() ? ob::PlannerStatus::TIMEOUT : ob::PlannerStatus::ABORT, context.str() + ": " + failure);
    insertSorted(detours, *detour);
    result_.obstacles.push_back(blocked.obstacle->name);
  }

  // Walk the path; whatever else blocks it on the line gets a detour too.
  JointWaypoints prefix;  // validated waypoints the next path shares
  prefix.joints.push_back(search.start);
  prefix.arcLengths.push_back(0.0);
  for (;;) {
    std::optional<ArcPath> path;
    try {
      path.emplace(search.a, search.b, detours);
    } catch (const Error& error) {
      std::string around;
      for (const std::string& name : result_.obstacles) around += (around.empty() ? "'" : ", '") + name + "'";
      return fail(ob::PlannerStatus::ABORT, "arc path around " + around + ": " + error.what());
    }
    const JointWaypoints walked = search.walk(*path, prefix);
    if (walked.ok()) {
      result_.kind = detours.empty() ? ArcPlannerResult::Kind::StraightLine : ArcPlannerResult::Kind::Detour;
      result_.detours = detours;
      result_.tcpPathLength = path->length();
      result_.waypointArcLengths = walked.arcLengths;
      solutionJoints_ = walked.joints;
      // The problem definition gets its own path: simplifying it must not change what this planner
      // reports (getPlannerData builds its states from solutionJoints_).
      auto path = std::make_shared<og::PathGeometric>(si_);
      for (const robot::Vector6& q : walked.joints) {
        search.toState(q, search.state);
        path->append(search.state);
      }
      pdef_->addSolutionPath(path, false, 0.0, getName());
      return ob::PlannerStatus::EXACT_SOLUTION;
    }
    if (ptc()) return fail(ob::PlannerStatus::TIMEOUT, "time limit reached before a valid path was found");
    const std::string where = detours.empty() ? "straight line" : "arc path";
    if (walked.status != ConversionStatus::Rejected) {
      return fail(ob::PlannerStatus::ABORT,
                  std::string(toString(walked.status)) + " on the " + where + ": " + walked.reason);
    }
    const double failedAt = walked.failedAtArcLength;
    const auto rejection = search.rejection();
    const collision::CollisionReport& pairs = rejection.pairs;
    const std::string why = rejection.describe(search.margin);
    std::ostringstream context;
    context << why << " on the " << where << " at TCP arc length " << failedAt << " m";
    for (std::size_t i = 0; i < detours.size(); ++i) {
      const auto [from, to] = path->detourSpan(i);
      if (failedAt > from && failedAt <= to + 1e-12) {
        std::ostringstream message;
        message << why << " on arc detour " << i + 1 << " around '"
                << result_.obstacles[std::min(i, result_.obstacles.size() - 1)] << "' at TCP arc length " << failedAt
                << " m";
        return fail(ob::PlannerStatus::ABORT, message.str());
      }
    }
    const ObstacleBall* obstacle = nullptr;
    for (const ObstacleBall& ball : obstacles_) {
      if (obstacle == nullptr && involves(pairs, ball.name)) obstacle = &ball;
    }
    if (obstacle == nullptr) {
      return fail(ob::PlannerStatus::ABORT, context.str() + ": no obstacle to go around (self-collision)");
    }
    if (std::find(result_.obstacles.begin(), result_.obstacles.end(), obstacle->name) != result_.obstacles.end() ||
        static_cast<int>(detours.size()) >= kMaxDetours) {
      return fail(ob::PlannerStatus::ABORT,
                  context.str() + ": '" + obstacle->name + "' still blocks the path after a detour around it");
    }
    // On a line piece the TCP is at distance u from A along the line.
    const double u = (path->position(failedAt) - search.a.translation()).dot(line.lineDirection());
    const double position =
        std::clamp((obstacle->center - search.a.translation()).dot(line.lineDirection()), 0.0, line.straightLength());
    Blockage blocked = blockage(search, line, *obstacle, u, search.rejectedJoints, pairs);
    blocked.position = position;
    std::string failure;
    const std::optional<Detour> detour = chooseDetour(search, detours, blocked, failure);
    if (!detour)
      return fail(ptc() ? ob::PlannerStatus::TIMEOUT : ob::PlannerStatus::ABORT, context.str() + ": " + failure);
    const std::size_t index = insertSorted(detours, *detour);
    result_.obstacles.insert(result_.obstacles.begin() + static_cast<std::ptrdiff_t>(index), obstacle->name);
    double entry = 0.0;
    try {
      entry = ArcPath(search.a, search.b, detours).detourSpan(index).first;
    } catch (const Error& error) {
      return fail(ob::PlannerStatus::ABORT, context.str() + ": " + error.what());
    }
    if (entry >= failedAt) {
      std::ostringstream message;
      message << ": the detour around '" << obstacle->name << "' leaves the line at " << entry
              << " m, after the collision; increase half_chord or the side radii";
      return fail(ob::PlannerStatus::ABORT, context.str() + message.str());
    }
    // Up to the entry the new path is the walked one.
    prefix = walked;
    while (prefix.arcLengths.back() > entry) {
      prefix.arcLengths.pop_back();
      prefix.joints.pop_back();
    }
  }
}

ArcPlanner::Blockage ArcPlanner::blockage(Search& search, const ArcPath& line, const ObstacleBall& obstacle, double u,
                                          const robot::Vector6& joints, const collision::CollisionReport& report) {
  Blockage blocked;
  blocked.obstacle = &obstacle;
  blocked.position = u;
  blocked.from = blocked.to = u;
  blocked.joints = joints;
  blocked.pairs = describeCollisions(report);
  if (!getAuto()) return blocked;  // only the search needs the extent
  // Follow the line both ways from u while the robot still hits the obstacle.
  const Eigen::Isometry3d here = line.pose(u);
  for (const bool forward : {true, false}) {
    const ArcPath stretch(here, forward ? search.b : search.a);
    const WaypointCheck stillBlocked = [&](const robot::Vector6&, const robot::Vector6& q, double arcLength) {
      if (!involves(collision::collide(*collisionModel_, search.data, q), obstacle.name)) return false;
      (forward ? blocked.to : blocked.from) = u + (forward ? arcLength : -arcLength);
      return true;
    };
    convertToJoints(ik_, stretch, joints, std::nullopt, conversion_, 0.0, std::numeric_limits<double>::infinity(),
                    stillBlocked);
  }
  return blocked;
}

std::optional<Detour> ArcPlanner::chooseDetour(Search& search, const std::vector<Detour>& chosen,
                                               const Blockage& blocked, std::string& failure) {
  if (!getAuto()) {
    const Detour detour{blocked.position, shape_, planeAngle_};
    try {
      validateArcParameters(shape_);
    } catch (const Error& error) {
      failure = error.what();
      return std::nullopt;
    }
    return detour;
  }
  // Candidates ordered by the length they add; the first valid one is the shortest. A given sagitta
  // is the smallest one searched.
  struct Candidate {
    Detour detour;
    double extraLength;
  };
  std::vector<Candidate> candidates;
  std::vector<double> sagittas{};
  if (shape_.sagitta > 0.0) sagittas.push_back(shape_.sagitta);
  for (const double h : kSearchSagittas) {
    if (h > shape_.sagitta) sagittas.push_back(h);
  }
  for (const double h : sagittas) {
    for (const double chordRatio : kSearchChordRatios) {
      for (const double entryRatio : kSearchRadiusRatios) {
        for (const double exitRatio : kSearchRadiusRatios) {
          const double r = chordRatio * h;
          const ArcParameters shape{h, r, entryRatio * r, exitRatio * r};
          const ArcDetourProfile profile = makeArcDetourProfile(shape);
          // The detour must replace the whole blocked stretch of the line.
          if (blocked.position - profile.entryOffset >= blocked.from ||
              blocked.position + profile.exitOffset <= blocked.to) {
            continue;
          }
          for (int k = 0; k < kSearchPlaneSteps; ++k) {
            const double angle = std::remainder(planeAngle_ + 2.0 * M_PI * k / kSearchPlaneSteps, 2.0 * M_PI);
            candidates.push_back({Detour{blocked.position, shape, angle}, profile.extraLength()});
          }
        }
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& x, const Candidate& y) { return x.extraLength < y.extraLength; });

  std::map<std::string, int> failures;
  int checked = 0, namedCollisions = 0;
  const auto collisionFailure = [&](const robot::Vector6& q) {
    if (namedCollisions++ < kNamedCollisionFailures) {
      failures["collision (" + describeCollisions(collision::collide(*collisionModel_, search.data, q)) + ")"]++;
    } else {
      failures["collision"]++;
    }
  };
  for (const Candidate& candidate : candidates) {
    if (search.ptc()) {
      failures["stopped by the time limit"]++;
      break;
    }
    std::vector<Detour> detours = chosen;
    const std::size_t index = insertSorted(detours, candidate.detour);
    std::optional<ArcPath> path;
    try {
      path.emplace(search.a, search.b, detours);
    } catch (const Error&) {
      failures["do not fit between A, B and the other detours"]++;
      continue;
    }
    ++checked;
    const auto [from, to] = path->detourSpan(index);
    // Quick rejection at the detour point nearest the obstacle, seeded with the blocked
    // configuration (same branch, so the posture the full conversion would find).
    double nearest = from, nearestDistance = std::numeric_limits<double>::infinity();
    for (double s = from; s <= to; s += 0.25 * conversion_.resolution) {
      const double distance = (path->position(s) - blocked.obstacle->center).squaredNorm();
      if (distance < nearestDistance) {
        nearestDistance = distance;
        nearest = s;
      }
    }
    // The thesis' circumscribed ball: the TCP stays outside the obstacle's bounding ball.
    if (std::sqrt(nearestDistance) < blocked.obstacle->radius) {
      failures["TCP inside the bounding ball"]++;
      continue;
    }
    const std::optional<robot::Vector6> probe = ik_.solveNearest(path->pose(nearest), blocked.joints);
    if (probe && !collision::isCollisionFree(*collisionModel_, search.data, *probe)) {
      collisionFailure(*probe);
      continue;
    }
    const std::optional<robot::Vector6> entry = ik_.solveNearest(path->pose(from), blocked.joints);
    if (!entry) {
      failures["unreachable"]++;
      continue;
    }
    const JointWaypoints span = convertToJoints(ik_, *path, *entry, std::nullopt, conversion_, from, to);
    if (!span.ok()) {
      failures[toString(span.status)]++;
      continue;
    }
    // Waypoints nearest the obstacle first: a failing candidate is usually rejected at once.
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t i = 0; i < span.joints.size(); ++i) {
      order.emplace_back((path->position(span.arcLengths[i]) - blocked.obstacle->center).squaredNorm(), i);
    }
    std::sort(order.begin(), order.end());
    bool valid = true;
    for (const auto& [distance, i] : order) {
      if (!collision::isCollisionFree(*collisionModel_, search.data, span.joints[i])) {
        collisionFailure(span.joints[i]);
        valid = false;
        break;
      }
    }
    for (std::size_t i = 1; valid && i < span.joints.size(); ++i) {
      if (!search.validMotion(span.joints[i - 1], span.joints[i], true)) {
        failures["collision between waypoints"]++;
        valid = false;
      }
    }
    if (valid) {
      result_.candidatesTried += checked;
      search.strict = true;
      return candidate.detour;
    }
  }
  result_.candidatesTried += checked;
  std::ostringstream message;
  message << "no arc detour around it is valid for the whole robot (" << candidates.size()
          << " shapes cover the blocked stretch, " << checked << " checked:";
  std::vector<std::pair<int, std::string>> ranked;
  for (const auto& [what, count] : failures) ranked.emplace_back(count, what);
  std::sort(ranked.rbegin(), ranked.rend());
  for (std::size_t i = 0; i < ranked.size() && i < 5; ++i) {
    message << (i > 0 ? "," : "") << " " << ranked[i].first << " " << ranked[i].second;
  }
  message << ")";
  failure = message.str();
  return std::nullopt;
}

void ArcPlanner::getPlannerData(ob::PlannerData& data) const {
  Planner::getPlannerData(data);
  const auto number = [](double value) {
    std::ostringstream text;
    text.precision(10);
    text << value;
    return text.str();
  };
  data.properties["solve time REAL"] = number(result_.solveTime);
  data.properties["arc detours INTEGER"] = std::to_string(result_.detours.size());
  data.properties["arc candidates INTEGER"] = std::to_string(result_.candidatesTried);
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
      for (int j = 0; j < 6; ++j) *si_->getStateSpace()->getValueAddressAtIndex(state, j) = q[j];
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
