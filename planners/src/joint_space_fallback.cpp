// The arc planner's fallback where no route through via points validates: a certified joint-space
// path from RRTConnect on the problem's SpaceInformation (or one keeping the planner's larger margin,
// ArcPlanner::fallbackSpace), shortened by OMPL's simplifier as `plan` and `bench` shorten RRTConnect's
// (kept only where every motion of the result is accepted), then (where it pays) with shortcuts for the
// TCP; then whichever executes fastest of that path, its segments as straight TCP lines where they validate for
// the whole robot, and mixes of the two — so the fallback is never slower than its own joint path. The
// result reports which share of its TCP length is Cartesian (docs/planners.md), so the arc planner
// is never a disguised RRTConnect. Its random numbers come from generators seeded by the planner's
// `seed` parameter, never from OMPL's process-wide seed: the same query gives the same path whatever
// else ran before in the process.
#include <ompl/base/MotionValidator.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <limits>
#include <optional>
#include <sstream>
#include <system_error>
#include <thread>

#include "arc_planning.h"
#include "arcplan/collision/joint_states.h"
#include "arcplan/common/error.h"
#include "arcplan/planners/certified_simplification.h"
#include "arcplan/planners/seeded_sampling.h"
#include "arcplan/robot/kinematics.h"

namespace arcplan::planners::detail {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// TCP length of a straight joint motion, from forward kinematics at this many points.
constexpr int kTcpSamples = 32;

// With its kinematics workspace allocated once (tipPose allocates one per call), the tip's chain alone placed.
class TcpLength {
public:
  explicit TcpLength(const robot::RobotModel& robot) : robot_(robot), data_(robot) {}

  double operator()(const robot::Vector6& from, const robot::Vector6& to) {
    double length = 0.0;
    Eigen::Vector3d previous = tip(from);
    for (int k = 1; k <= kTcpSamples; ++k) {
      const Eigen::Vector3d p = tip(from + (to - from) * (static_cast<double>(k) / kTcpSamples));
      length += (p - previous).norm();
      previous = p;
    }
    return length;
  }

private:
  Eigen::Vector3d tip(const robot::Vector6& q) {
    robot::chainKinematics(robot_, q, robot_.tipLink(), data_);
    return data_.linkPoses[robot_.tipLink()].translation();
  }

  const robot::RobotModel& robot_;
  robot::KinematicsData data_;
};

// The space one plan runs on: the states of `checked` (its validity checker, shared) and `motions` on a
// joint space of its own whose samplers are allocated as in a campaign run seeded with the plan's seed
// (seededSamplerAllocator): RRTConnect's first, then the one OMPL's simplifier allocates when it repairs a
// path. On the problem's own space the simplifier's would come from whatever allocator that space has
// (bookshelf_thin_ur5-0078 of MBM: its first plan executed in 9.76 s instead of RRTConnect + simplifier's
// 9.50 s with the same run seed).
ob::SpaceInformationPtr seededSpace(const ob::SpaceInformationPtr& checked, const ob::MotionValidatorPtr& motions,
                                    std::uint32_t samplerSeed) {
  const auto* joints = dynamic_cast<const ob::RealVectorStateSpace*>(checked->getStateSpace().get());
  if (joints == nullptr) throw Error("arc planner fallback: the joint space must be a RealVectorStateSpace");
  auto space = std::make_shared<ob::RealVectorStateSpace>(joints->getDimension());
  space->setBounds(joints->getBounds());
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(checked->getStateValidityChecker());
  si->setMotionValidator(motions);
  si->setStateValidityCheckingResolution(checked->getStateValidityCheckingResolution());
  si->setup();
  // After setup, whose sanity checks draw states of their own.
  space->setStateSamplerAllocator(seededSamplerAllocator(samplerSeed));
  return si;
}

// The motions of a later plan: the problem's motion validator until the caller's time is up, then every
// motion refused at once. OMPL's simplifier polls the termination condition only between its steps, and
// one step can check hundreds of certified motions (smoothBSpline's subdivisions: MBM's
// bookshelf_tall_ur5-0011, its first plan simplified within the limit, ran 0.63 s past a 0.4 s limit in the
// step under way). Refusing only ever keeps the path as it was, and a plan cut by the limit is dropped anyway.
class MotionsUntilTheLimit : public ob::MotionValidator {
public:
  MotionsUntilTheLimit(const ob::SpaceInformationPtr& checked, const ob::PlannerTerminationCondition& ptc)
      : ob::MotionValidator(checked), checked_(checked->getMotionValidator()), ptc_(ptc) {}
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    return !ptc_() && checked_->checkMotion(s1, s2);
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& lastValid) const override {
    if (!ptc_()) return checked_->checkMotion(s1, s2, lastValid);
    if (lastValid.first != nullptr) si_->copyState(lastValid.first, s1);
    lastValid.second = 0.0;
    return false;
  }

private:
  ob::MotionValidatorPtr checked_;
  const ob::PlannerTerminationCondition& ptc_;
};

// How a plan is simplified. The first plan to the end (simplifyMax), whatever the time limit: a benchmark
// run simplifies RRTConnect's path after its solve, untimed, and the first plan must be that path for the
// fallback to be never slower than RRTConnect + simplifier of the same seed (docs/planners.md, "Fallback").
// Later plans only within the limit.
enum class Simplification { ToTheEnd, WithinTheLimit };

struct JointPlan {
  std::vector<robot::Vector6> waypoints;
  double simplificationTime = 0.0;  // s: the simplifier's and the check of its result
};

// RRTConnect's path from start to goal, simplified, drawing from the streams `seed` fixes
// (seeded_sampling.h): what a benchmark run seeded with `seed` computes for RRTConnect (solve, then
// SimpleSetup::simplifySolution(), i.e. PathSimplifier::simplifyMax with the problem's goal) on the same
// states and motions (seededSpace), with RRTConnect's `range` set to `range` (0: left at its default).
// WithinTheLimit: identical until the caller's termination condition fires, then no motion is checked
// (MotionsUntilTheLimit); a plan the limit cuts is of no use to the caller, which keeps an earlier one, so
// it is returned unsimplified and unchecked.
std::optional<JointPlan> simplifiedJointPath(const ArcQuery& query, const ob::SpaceInformationPtr& checked,
                                             std::uint_fast32_t seed, double range, Simplification simplification) {
  const SamplingSeeds seeds = samplingSeeds(seed);
  const ob::SpaceInformationPtr si = seededSpace(checked,
                                                 simplification == Simplification::ToTheEnd
                                                     ? checked->getMotionValidator()
                                                     : std::make_shared<MotionsUntilTheLimit>(checked, query.ptc),
                                                 seeds.sampler);
  auto problem = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<> start(si), goal(si);
  collision::setJoints(start.get(), query.start);
  collision::setJoints(goal.get(), query.goal);
  problem->setStartAndGoalStates(start, goal);
  og::RRTConnect planner(si);
  if (range > 0.0) planner.setRange(range);
  planner.setProblemDefinition(problem);
  planner.setup();
  if (planner.solve(query.ptc) != ob::PlannerStatus::EXACT_SOLUTION) return std::nullopt;
  og::PathGeometric path(*problem->getSolutionPath()->as<og::PathGeometric>());
  const auto simplifier = makeSeededSimplifier(si, *problem, seeds.simplifier);
  const auto clockStart = std::chrono::steady_clock::now();
  // The result only where the motion validator accepts all of it (certified_simplification.h): otherwise
  // RRTConnect's own path, every motion of which it accepted.
  simplifyKeepingCertified(*si, path, [&](og::PathGeometric& p) {
    if (simplification == Simplification::ToTheEnd) return simplifier->simplifyMax(p);
    // Without OMPL's default (atLeastOnce) a whole pass would run after the condition fired (up to 490
    // more certified motion checks on forearm-beam-009): the step under way when time is up is the last.
    return simplifier->simplify(p, query.ptc, false) && !query.ptc();
  });
  return JointPlan{collision::waypointsOf(path),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - clockStart).count()};
}

// Shortcuts for the tool. OMPL's simplifier shortens the path in joint space, but its execution time at
// a TCP speed limit goes with the TCP's path length: random pairs of points on the path (from a generator
// seeded like the rest) are joined by a straight joint motion where the motion validator accepts it
// and the TCP travels less on it than on the part it replaces. Each attempt costs a few forward
// kinematics and at most one certified motion check.
constexpr int kTcpShortcuts = 150;

struct PathPoint {
  std::size_t segment;  // the point lies on the motion path[segment] -> path[segment + 1]
  robot::Vector6 q;
};

PathPoint pointAt(const std::vector<robot::Vector6>& path, const std::vector<double>& at, double s) {
  std::size_t i = 0;
  while (i + 2 < path.size() && at[i + 1] <= s) ++i;
  const double span = at[i + 1] - at[i];
  return {i, path[i] + (path[i + 1] - path[i]) * (span > 0.0 ? std::clamp((s - at[i]) / span, 0.0, 1.0) : 0.0)};
}

std::vector<robot::Vector6> tcpShortcuts(const ArcQuery& query, const ob::SpaceInformationPtr& si,
                                         std::vector<robot::Vector6> path, std::uint_fast32_t seed) {
  TcpLength tcpLengthOf(query.model.robot());
  ompl::RNG rng;
  rng.setLocalSeed(seed);
  ob::ScopedState<> from(si), to(si);
  // Per motion of `path`, its TCP length: measured once per path, not once per attempt that spans it.
  std::vector<double> motionLengths;
  for (int attempt = 0; attempt < kTcpShortcuts && path.size() > 2 && !query.ptc(); ++attempt) {
    if (motionLengths.empty()) {
      for (std::size_t k = 0; k + 1 < path.size(); ++k) motionLengths.push_back(tcpLengthOf(path[k], path[k + 1]));
    }
    std::vector<double> at{0.0};
    for (std::size_t i = 1; i < path.size(); ++i) at.push_back(at.back() + (path[i] - path[i - 1]).norm());
    double s1 = rng.uniformReal(0.0, at.back()), s2 = rng.uniformReal(0.0, at.back());
    if (s1 > s2) std::swap(s1, s2);
    const PathPoint a = pointAt(path, at, s1), b = pointAt(path, at, s2);
    if (a.segment == b.segment) continue;  // a straight motion already
    double replaced = tcpLengthOf(a.q, path[a.segment + 1]) + tcpLengthOf(path[b.segment], b.q);
    for (std::size_t k = a.segment + 1; k < b.segment; ++k) replaced += motionLengths[k];
    if (tcpLengthOf(a.q, b.q) >= replaced - 1e-4) continue;
    collision::setJoints(from.get(), a.q);
    collision::setJoints(to.get(), b.q);
    if (!si->checkMotion(from.get(), to.get())) continue;
    std::vector<robot::Vector6> shorter(path.begin(), path.begin() + static_cast<std::ptrdiff_t>(a.segment) + 1);
    for (const robot::Vector6& q : {a.q, b.q}) {
      if ((q - shorter.back()).norm() > 1e-12) shorter.push_back(q);
    }
    for (std::size_t k = b.segment + 1; k < path.size(); ++k) {
      if ((path[k] - shorter.back()).norm() > 1e-12) shorter.push_back(path[k]);
    }
    path = std::move(shorter);
    motionLengths.clear();
  }
  return path;
}

// One segment of the simplified joint path: the joint motion RRTConnect found and, where it validates,
// the same segment as a straight TCP line (its waypoints, arc lengths from the segment's start).
struct Segment {
  robot::Vector6 from, to;
  double jointTcpLength = 0.0;
  std::optional<JointConversionResult> line;
  double lineLength = 0.0;
};

// With `asLines`, each segment also as its TCP line where that validates (a walk each, cut short by the
// termination condition); without, joint motions only.
std::vector<Segment> segmentsOf(const ArcQuery& query, const std::vector<robot::Vector6>& simplified, bool asLines) {
  std::vector<Segment> segments;
  TcpLength tcpLengthOf(query.model.robot());
  for (std::size_t i = 1; i < simplified.size(); ++i) {
    Segment segment;
    segment.from = simplified[i - 1];
    segment.to = simplified[i];
    segment.jointTcpLength = tcpLengthOf(segment.from, segment.to);
    if (!asLines) {
      segments.push_back(std::move(segment));
      continue;
    }
    const ArcPath line(robot::tipPose(query.model.robot(), segment.from),
                       robot::tipPose(query.model.robot(), segment.to));
    JointConversionResult here;
    here.joints.push_back(segment.from);
    here.arcLengths.push_back(0.0);
    Walk walked = query.validator.walk(line, here, segment.to);
    if (walked.ok()) {
      segment.line = std::move(walked.waypoints);
      segment.lineLength = line.length();
    }
    segments.push_back(std::move(segment));
  }
  return segments;
}

// The path with segment k as its TCP line where asLine[k], else as the joint motion (certified by the
// SpaceInformation's motion validator).
ArcOutcome pathOf(const ArcQuery& query, const std::vector<Segment>& segments, const std::vector<bool>& asLine) {
  ArcOutcome outcome;
  outcome.kind = ArcPlannerResult::Kind::Fallback;
  JointConversionResult& waypoints = outcome.path;
  waypoints = query.startOnly();
  double cartesian = 0.0, total = 0.0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const Segment& segment = segments[k];
    const double offset = waypoints.arcLengths.back();
    if (asLine[k]) {
      for (std::size_t i = 1; i < segment.line->joints.size(); ++i) {
        waypoints.joints.push_back(segment.line->joints[i]);
        waypoints.arcLengths.push_back(offset + segment.line->arcLengths[i]);
      }
      cartesian += segment.lineLength;
      total += segment.lineLength;
    } else {
      waypoints.joints.push_back(segment.to);
      waypoints.arcLengths.push_back(offset + segment.jointTcpLength);
      total += segment.jointTcpLength;
    }
  }
  outcome.cartesianFraction = total > 0.0 ? cartesian / total : 0.0;
  outcome.tcpPathLength = cartesian;
  return outcome;
}

// Which of the joint-space path, its segments as lines where they validate, and mixes of the two
// executes fastest at the speed limit: turning a joint motion into a TCP line can make it slower (the
// line's corners slow the tool down, its joints may move farther), so lines are kept only where they
// pay. Mixes: from the faster of the two, one segment at a time switched where that is faster.
// `jointTime` is the joint path's, timed by the caller. Each candidate costs a time scaling (10-60 ms on
// MBM) unless its planned profile (timing.lowerBound) is already slower: once time is up, none is timed and
// the joint path is kept.
ArcOutcome fastestPath(const ArcQuery& query, const std::vector<Segment>& segments, const ExecutionTiming& timing,
                       double jointTime) {
  const auto jointsOf = [&](const std::vector<bool>& asLine) { return pathOf(query, segments, asLine).path.joints; };
  const std::vector<bool> jointPath(segments.size(), false);
  std::vector<bool> allLines;
  for (const Segment& segment : segments) allLines.push_back(segment.line.has_value() && !query.ptc());
  const double lineTime = allLines == jointPath ? jointTime : timing.time(jointsOf(allLines));
  std::vector<bool> kept = lineTime <= jointTime ? allLines : jointPath;
  double keptTime = std::min(lineTime, jointTime);
  for (std::size_t k = 0; k < segments.size() && !query.ptc(); ++k) {
    if (!allLines[k]) continue;
    std::vector<bool> mixed = kept;
    mixed[k] = !mixed[k];
    const std::vector<robot::Vector6> joints = jointsOf(mixed);
    if (timing.slowerThan(joints, keptTime)) continue;
    const double time = timing.time(joints);
    if (time >= keptTime) continue;
    kept = std::move(mixed);
    keptTime = time;
  }
  ArcOutcome outcome = pathOf(query, segments, kept);
  outcome.fallbackTimes = {jointTime, lineTime, keptTime};
  const auto lines = static_cast<std::size_t>(std::count(kept.begin(), kept.end(), true));
  std::ostringstream reason;
  reason << "the fallback kept "
         << (kept == allLines && lines > 0 ? "its segments as TCP lines"
             : lines == 0                  ? "the joint-space path"
                                           : "a mix")
         << " (" << lines << " of " << segments.size() << " segments as lines): " << keptTime
         << " s to execute; the joint-space path " << jointTime << " s, as lines where they validate " << lineTime
         << " s";
  outcome.reason = reason.str();
  return outcome;
}

// Plan k of the fallback: RRTConnect + simplifier of seed + k, the first simplified to the end, later ones within the
// caller's limit.
std::optional<JointPlan> planNumber(const ArcQuery& query, const ob::SpaceInformationPtr& si,
                                    const JointPlanSettings& settings, std::uint_fast32_t k) {
  return simplifiedJointPath(query, si, settings.seed + k, settings.range,
                             k == 0 ? Simplification::ToTheEnd : Simplification::WithinTheLimit);
}

// The plans (and each plan's shortcuts for the TCP) drawn on `threads` threads at once: each depends only on its own
// seed, so each is what the serial loop of planInJointSpace draws, and that loop then takes them in order. Later plans
// are not started once the caller's time is up. An exception of any draw is rethrown here after all threads ended.
struct DrawnPlans {
  std::vector<std::optional<JointPlan>> plans;
  std::vector<std::vector<robot::Vector6>> shortcuts;
};

DrawnPlans drawPlans(const ArcQuery& query, const ob::SpaceInformationPtr& si, const JointPlanSettings& settings) {
  DrawnPlans drawn;
  drawn.plans.resize(settings.plans);
  drawn.shortcuts.resize(settings.plans);
  std::atomic<std::uint_fast32_t> next{0};
  std::vector<std::exception_ptr> errors(settings.threads);
  const auto draw = [&](std::size_t worker) {
    try {
      for (std::uint_fast32_t k = next++; k < settings.plans; k = next++) {
        if (k > 0 && query.ptc()) continue;
        drawn.plans[k] = planNumber(query, si, settings, k);
        if (drawn.plans[k]) drawn.shortcuts[k] = tcpShortcuts(query, si, drawn.plans[k]->waypoints, settings.seed + k);
      }
    } catch (...) {
      errors[worker] = std::current_exception();
    }
  };
  std::vector<std::thread> workers;
  for (std::size_t worker = 1; worker < settings.threads; ++worker) {
    try {
      workers.emplace_back(draw, worker);
    } catch (const std::system_error&) {
      break;  // no thread to be had: the threads there are draw the rest
    }
  }
  draw(0);
  for (std::thread& worker : workers) worker.join();
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  return drawn;
}

}  // namespace

ArcOutcome planInJointSpace(const ArcQuery& query, const ob::SpaceInformationPtr& si, const JointPlanSettings& settings,
                            const ExecutionTiming& timing) {
  constexpr double kSlower = std::numeric_limits<double>::infinity();  // a time known to lose, not measured
  const std::uint_fast32_t seed = settings.seed;
  // Each plan, RRTConnect + simplifier, counts as it is and with shortcuts for the TCP (kept only where
  // they execute faster); the fastest path goes on to the line conversion.
  std::optional<std::vector<robot::Vector6>> fastest;
  // the path kept so far; the fastest plan as it came; the first plan as it came
  double fastestTime = 0.0, fastestPlan = 0.0, firstPlan = 0.0, firstSimplification = 0.0;
  int plans = 0;
  // Once time is up the fallback returns the best path it has timed: a later plan that ends after the
  // limit is dropped untimed (a time scaling costs 10-60 ms on MBM), and no line is tried.
  // Joint-space plans (seeds seed, seed + 1, ...) of which the fastest to execute is kept (settings.plans, 4 by
  // default): one RRTConnect + simplifier path can take twice as long as the next draw's (generated line-cylinder-008:
  // 7.73 s with seed 1, 5.55 s for the benchmark's RRTConnect run), and each costs about as much as the search. Later
  // plans only while the termination condition allows.
  // With more than one thread the plans are drawn first, all at once (drawPlans), and taken here in order.
  const bool drawnAtOnce = settings.threads > 1 && settings.plans > 1;
  DrawnPlans drawn = drawnAtOnce ? drawPlans(query, si, settings) : DrawnPlans{};
  for (std::uint_fast32_t k = 0; k < settings.plans && (k == 0 || !query.ptc()); ++k) {
    std::optional<JointPlan> planned = drawnAtOnce ? std::move(drawn.plans[k]) : planNumber(query, si, settings, k);
    if (!planned || (fastest && query.ptc())) continue;
    std::vector<robot::Vector6>& path = planned->waypoints;
    // The first plan is timed (it is reported), a later one only where its planned profile leaves it a chance of
    // being the fastest plan as it came; a shortcut only where it may beat the plan and every path so far.
    const bool firstTimed = plans++ == 0;
    const double planTime = k == 0 || firstTimed || !timing.slowerThan(path, fastestPlan) ? timing.time(path) : kSlower;
    if (k == 0) {
      firstPlan = planTime;
      firstSimplification = planned->simplificationTime;
    }
    fastestPlan = firstTimed ? planTime : std::min(fastestPlan, planTime);
    std::vector<robot::Vector6> shortcut =
        drawnAtOnce ? std::move(drawn.shortcuts[k]) : tcpShortcuts(query, si, path, seed + k);
    const double toBeat = fastest ? std::min(fastestTime, planTime) : planTime;
    const double shortcutTime =
        shortcut == path || timing.slowerThan(shortcut, toBeat) ? planTime : timing.time(shortcut);
    if (shortcutTime < planTime) path = std::move(shortcut);
    const double time = std::min(planTime, shortcutTime);
    if (fastest && time >= fastestTime) continue;
    fastest = std::move(path);
    fastestTime = time;
  }
  if (!fastest) return failure("the joint-space fallback found no path either");
  ArcOutcome outcome = fastestPath(query, segmentsOf(query, *fastest, !query.ptc()), timing, fastestTime);
  outcome.fallbackTimes.jointPath = fastestPlan;
  outcome.fallbackTimes.firstPlan = firstPlan;
  outcome.simplificationTime = firstSimplification;
  std::ostringstream plansText;
  plansText << " (with shortcuts for the TCP where they pay; the fastest of " << plans
            << " RRTConnect + simplifier plans as they came: " << fastestPlan << " s)";
  outcome.reason += plansText.str();
  return outcome;
}

}  // namespace arcplan::planners::detail
