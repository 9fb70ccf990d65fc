// The arc planner's fallback where no route through via points validates: a certified joint-space
// path from RRTConnect on the planner's own SpaceInformation, shortened by OMPL's simplifier, with
// each segment replaced by a straight TCP line where that line validates for the whole robot. The
// result reports which share of its TCP length is Cartesian (docs/planners.md), so the arc planner
// is never a disguised RRTConnect. Its random numbers come from generators seeded by the planner's
// `seed` parameter, never from OMPL's process-wide seed: the same query gives the same path whatever
// else ran before in the process.
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include "arc_planning.h"
#include "arcplan/collision/joint_states.h"
#include "arcplan/robot/kinematics.h"

namespace arcplan::planners::detail {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// TCP length of a straight joint motion, from forward kinematics at this many points.
constexpr int kTcpSamples = 32;

double tcpLengthOf(const robot::RobotModel& robot, const robot::Vector6& from, const robot::Vector6& to) {
  double length = 0.0;
  Eigen::Vector3d previous = robot::tipPose(robot, from).translation();
  for (int k = 1; k <= kTcpSamples; ++k) {
    const Eigen::Vector3d p =
        robot::tipPose(robot, from + (to - from) * (static_cast<double>(k) / kTcpSamples)).translation();
    length += (p - previous).norm();
    previous = p;
  }
  return length;
}

// OMPL's uniform sampler of the joint box, drawing from its own seeded generator.
class SeededJointSampler : public ob::RealVectorStateSampler {
public:
  SeededJointSampler(const ob::StateSpace* space, std::uint_fast32_t seed) : RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

// RRTConnect whose samples (and any other draw) come from seeded generators. RRTConnect allocates
// its sampler in solve() only when it has none, so the seeded one set after setup() is used.
class SeededRRTConnect : public og::RRTConnect {
public:
  SeededRRTConnect(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed) : RRTConnect(si), seed_(seed) {
    rng_.setLocalSeed(seed);
  }
  void setup() override {
    RRTConnect::setup();
    sampler_ = std::make_shared<SeededJointSampler>(si_->getStateSpace().get(), seed_);
  }

private:
  std::uint_fast32_t seed_;
};

// OMPL's simplifier (shortcuts between random points) drawing from a seeded generator.
class SeededSimplifier : public og::PathSimplifier {
public:
  SeededSimplifier(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed) : PathSimplifier(si) {
    rng_.setLocalSeed(seed);
  }
};

// The simplified joint path with each segment replaced by a straight TCP line where that line validates.
ArcOutcome linesWhereTheyValidate(const ArcQuery& query, const std::vector<robot::Vector6>& simplified) {
  ArcOutcome outcome;
  outcome.kind = ArcPlannerResult::Kind::Fallback;
  JointConversionResult& waypoints = outcome.path;
  waypoints = query.startOnly();
  double cartesian = 0.0, total = 0.0;
  for (std::size_t i = 1; i < simplified.size(); ++i) {
    const robot::Vector6 from = waypoints.joints.back(), to = simplified[i];
    const ArcPath line(robot::tipPose(query.model.robot(), from), robot::tipPose(query.model.robot(), to));
    JointConversionResult here;
    here.joints.push_back(from);
    here.arcLengths.push_back(0.0);
    const Walk walked = query.validator.walk(line, here, to);
    const double offset = waypoints.arcLengths.back();
    if (walked.ok()) {  // the segment as a TCP line
      for (std::size_t k = 1; k < walked.waypoints.joints.size(); ++k) {
        waypoints.joints.push_back(walked.waypoints.joints[k]);
        waypoints.arcLengths.push_back(offset + walked.waypoints.arcLengths[k]);
      }
      cartesian += line.length();
      total += line.length();
    } else {  // the joint motion RRTConnect found, certified by the SpaceInformation's motion validator
      const double length = tcpLengthOf(query.model.robot(), from, to);
      waypoints.joints.push_back(to);
      waypoints.arcLengths.push_back(offset + length);
      total += length;
    }
  }
  outcome.cartesianFraction = total > 0.0 ? cartesian / total : 0.0;
  outcome.tcpPathLength = cartesian;
  return outcome;
}

}  // namespace

ArcOutcome planInJointSpace(const ArcQuery& query, const ob::SpaceInformationPtr& si, std::uint_fast32_t seed) {
  auto problem = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<> start(si), goal(si);
  collision::setJoints(start.get(), query.start);
  collision::setJoints(goal.get(), query.goal);
  problem->setStartAndGoalStates(start, goal);
  SeededRRTConnect sampler(si, seed);
  sampler.setProblemDefinition(problem);
  sampler.setup();
  if (sampler.solve(query.ptc) != ob::PlannerStatus::EXACT_SOLUTION) {
    return failure("the joint-space fallback found no path either");
  }
  og::PathGeometric path(*problem->getSolutionPath()->as<og::PathGeometric>());
  SeededSimplifier(si, seed).simplify(path, query.ptc);
  return linesWhereTheyValidate(query, collision::waypointsOf(path));
}

}  // namespace arcplan::planners::detail
