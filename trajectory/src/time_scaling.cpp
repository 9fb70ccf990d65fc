#include "arcplan/trajectory/time_scaling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/trajectory/path_densification.h"
#include "arcplan/trajectory/pchip.h"

namespace arcplan::trajectory {
namespace {

// The speed profile is planned along a path parameter sigma that is the TCP arc length wherever
// the TCP moves, and counts joint motion at this many metres per radian where it (almost) does not
// (a pure wrist rotation), so such stretches get a finite duration and a bounded ramp.
constexpr double kReorientationLength = 0.1;
// An interval whose samples are too fast is stretched by the excess ratio plus this margin, so the
// check converges in a few rounds instead of creeping towards the limit.
constexpr double kStretchMargin = 1e-3;
// After this many rounds of local stretching the whole timing is scaled (exact for PCHIP, whose
// derivatives scale with 1/factor), which always terminates.
constexpr int kLocalRounds = 25;
constexpr double kLocalGridRefinement = 4.0;
// The profile cruises this fraction below the TCP limit: the interpolated motion differs from the
// planned one by O(step²) (a few 1e-5 relative at the default steps), which would otherwise make
// the check stretch nearly every cruise interval.
constexpr double kPlanningHeadroom = 5e-4;

void requirePositive(double value, const std::string& name, const std::string& unit) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw Error("time scaling: " + name + " must be a positive finite number (" + unit + "), got " +
                std::to_string(value));
  }
}

void validateOptions(const TimeScalingOptions& options) {
  requirePositive(options.maxTcpSpeed, "maxTcpSpeed", "m/s");
  if (options.maxTcpAcceleration) {
    requirePositive(*options.maxTcpAcceleration, "maxTcpAcceleration", "m/s²");
  } else {
    requirePositive(options.riseTime, "riseTime", "s");
  }
  requirePositive(options.checkTimeStep, "checkTimeStep", "s");
  requirePositive(options.maxJointStep, "maxJointStep", "rad");
  requirePositive(options.maxTcpStep, "maxTcpStep", "m");
}

robot::Vector6 jointSpeedLimitsOf(const robot::RobotModel& model) {
  robot::Vector6 limits;
  for (int j = 0; j < 6; ++j) {
    limits[j] = model.joints()[j].limits.velocity;
    if (!(limits[j] > 0.0) || !std::isfinite(limits[j])) {
      throw Error("time scaling: joint " + model.joints()[j].name + " of robot " + model.name() +
                  " has no positive velocity limit in its URDF");
    }
  }
  return limits;
}

// Ramp–cruise–brake profile along sigma at the dense path's waypoints: speed limits per segment
// (TCP and joints), constant acceleration forward from rest and backward to rest, and the times it
// reaches each waypoint (constant acceleration within a segment).
struct PlannedProfile {
  std::vector<double> sigma;  // path parameter at the waypoints
  std::vector<double> speed;  // d sigma / dt at the waypoints
  std::vector<double> time;   // s
};

PlannedProfile planProfile(const DensePath& dense, const robot::Vector6& jointSpeedLimits, double maxTcpSpeed,
                           double acceleration) {
  const std::size_t segments = dense.waypoints.size() - 1;
  PlannedProfile profile;
  profile.sigma.assign(segments + 1, 0.0);
  std::vector<double> limit(segments);
  for (std::size_t k = 0; k < segments; ++k) {
    const double tcpStep = dense.tcpArcLength[k + 1] - dense.tcpArcLength[k];
    const robot::Vector6 jointStep = dense.waypoints[k + 1] - dense.waypoints[k];
    const double length = std::max(tcpStep, kReorientationLength * jointStep.norm());
    profile.sigma[k + 1] = profile.sigma[k] + length;
    double sigmaSpeed = tcpStep > 0.0 ? maxTcpSpeed * length / tcpStep : std::numeric_limits<double>::infinity();
    for (int j = 0; j < 6; ++j) {
      if (jointStep[j] != 0.0) sigmaSpeed = std::min(sigmaSpeed, jointSpeedLimits[j] * length / std::abs(jointStep[j]));
    }
    limit[k] = sigmaSpeed;
  }
  auto& speed = profile.speed;
  speed.assign(segments + 1, 0.0);  // at rest at both ends
  for (std::size_t k = 1; k < segments; ++k) speed[k] = std::min(limit[k - 1], limit[k]);
  const auto reachable = [&](double fromSpeed, std::size_t k) {
    return std::sqrt(fromSpeed * fromSpeed + 2.0 * acceleration * (profile.sigma[k + 1] - profile.sigma[k]));
  };
  for (std::size_t k = 0; k < segments; ++k) speed[k + 1] = std::min(speed[k + 1], reachable(speed[k], k));
  for (std::size_t k = segments; k-- > 0;) speed[k] = std::min(speed[k], reachable(speed[k + 1], k));
  profile.time.assign(segments + 1, 0.0);
  for (std::size_t k = 0; k < segments; ++k) {
    // Both ends at rest only for a single segment, which the caller avoids.
    profile.time[k + 1] = profile.time[k] + 2.0 * (profile.sigma[k + 1] - profile.sigma[k]) / (speed[k] + speed[k + 1]);
  }
  return profile;
}

// PCHIP's slope estimate (a harmonic mean of the neighbouring secants) is accurate when the knots
// are evenly spaced in time, but the dense waypoints are evenly spaced along the path, so in the
// ramps their time steps vary several-fold and the interpolated acceleration saw-tooths. The knots
// are therefore placed on a uniform time grid of the planned profile, on the dense path's joint
// segments, with a step that keeps them at most one densification step apart.
void placeKnots(const DensePath& dense, const PlannedProfile& profile, const TimeScalingOptions& options,
                JointPath& knots, std::vector<double>& knotTimes) {
  const std::size_t segments = dense.waypoints.size() - 1;
  double knotStep = profile.time.back() / 2.0;
  for (std::size_t k = 0; k < segments; ++k) {
    const double duration = profile.time[k + 1] - profile.time[k];
    const double tcpStep = dense.tcpArcLength[k + 1] - dense.tcpArcLength[k];
    const double jointStep = (dense.waypoints[k + 1] - dense.waypoints[k]).cwiseAbs().maxCoeff();
    double fraction = options.maxJointStep / jointStep;
    if (tcpStep > 0.0) fraction = std::min(fraction, options.maxTcpStep / tcpStep);
    knotStep = std::min(knotStep, duration * fraction);
  }
  const auto intervals = static_cast<std::size_t>(std::ceil(profile.time.back() / knotStep - 1e-9));
  knots.resize(intervals + 1);
  knotTimes.resize(intervals + 1);
  std::size_t k = 0;
  for (std::size_t i = 0; i <= intervals; ++i) {
    const double t = profile.time.back() * static_cast<double>(i) / static_cast<double>(intervals);
    while (k + 1 < segments && t > profile.time[k + 1]) ++k;
    const double duration = profile.time[k + 1] - profile.time[k];
    const double tau = std::clamp(t - profile.time[k], 0.0, duration);
    const double accelerationInSegment = (profile.speed[k + 1] - profile.speed[k]) / duration;
    const double travelled = profile.speed[k] * tau + 0.5 * accelerationInSegment * tau * tau;
    const double fraction = std::clamp(travelled / (profile.sigma[k + 1] - profile.sigma[k]), 0.0, 1.0);
    knots[i] = dense.waypoints[k] + fraction * (dense.waypoints[k + 1] - dense.waypoints[k]);
    knotTimes[i] = t;
  }
  knots.front() = dense.waypoints.front();
  knots.back() = dense.waypoints.back();
}

void cumulativeTimes(const std::vector<double>& duration, std::vector<double>& times) {
  times.resize(duration.size() + 1);
  times[0] = 0.0;
  for (std::size_t k = 0; k < duration.size(); ++k) times[k + 1] = times[k] + duration[k];
}

std::vector<double> intervalDurations(const std::vector<double>& times) {
  std::vector<double> duration(times.size() - 1);
  for (std::size_t k = 0; k < duration.size(); ++k) duration[k] = times[k + 1] - times[k];
  return duration;
}

// Knot intervals around the dense waypoints where the planned acceleration changes by more than 1 %
// of the acceleration limit (and their neighbours).
std::vector<std::size_t> intervalsAtProfileCorners(const PlannedProfile& profile, const std::vector<double>& knotTimes,
                                                   double acceleration) {
  std::vector<std::size_t> intervals;
  const std::size_t lastInterval = knotTimes.size() - 2;
  double previousAcceleration = 0.0;
  std::size_t knot = 0;
  for (std::size_t k = 0; k + 1 < profile.time.size(); ++k) {
    const double segmentAcceleration =
        (profile.speed[k + 1] - profile.speed[k]) / (profile.time[k + 1] - profile.time[k]);
    if (k > 0 && std::abs(segmentAcceleration - previousAcceleration) > 0.01 * acceleration) {
      while (knot < lastInterval && knotTimes[knot + 1] <= profile.time[k]) ++knot;
      for (std::size_t i = knot > 0 ? knot - 1 : 0; i <= std::min(knot + 1, lastInterval); ++i) {
        if (intervals.empty() || intervals.back() < i) intervals.push_back(i);
      }
    }
    previousAcceleration = segmentAcceleration;
  }
  return intervals;
}

// Evaluates the interpolated motion and compares it with the limits. Keeps the per-interval
// stretch factors that would bring every offending sample back under its limit.
class LimitCheck {
public:
  LimitCheck(const robot::RobotModel& model, const TimeScalingOptions& options, const robot::Vector6& jointSpeedLimits,
             std::size_t intervals)
      : model_(model),
        kinematics_(model),
        maxTcpSpeed_(options.maxTcpSpeed),
        jointSpeedLimits_(jointSpeedLimits),
        stretch_(intervals, 1.0) {}

  // Samples the uniform output grid (step <= checkTimeStep), into `result` where one is given (else only checked).
  void sampleAll(const Pchip& motion, double checkTimeStep, TimedTrajectory* result) {
    const auto& knots = motion.knots();
    const double totalTime = knots.back();
    const auto sampleCount = static_cast<std::size_t>(std::ceil(totalTime / checkTimeStep - 1e-9)) + 1;
    const double step = totalTime / static_cast<double>(sampleCount - 1);
    if (result != nullptr) {
      result->time.resize(sampleCount);
      result->position.resize(sampleCount);
      result->velocity.resize(sampleCount);
      result->acceleration.resize(sampleCount);
      result->tcpSpeed.resize(sampleCount);
      result->tcpPosition.resize(sampleCount);
    }
    std::size_t interval = 0;
    for (std::size_t i = 0; i < sampleCount; ++i) {
      const double t = i + 1 == sampleCount ? totalTime : step * static_cast<double>(i);
      while (interval + 2 < knots.size() && t >= knots[interval + 1]) ++interval;
      robot::Vector6& position = result != nullptr ? result->position[i] : position_;
      robot::Vector6& velocity = result != nullptr ? result->velocity[i] : velocity_;
      robot::Vector6& acceleration = result != nullptr ? result->acceleration[i] : acceleration_;
      motion.evaluateInInterval(interval, t, position, velocity, acceleration);
      const double speed = tcpSpeed(position, velocity, result != nullptr ? &result->tcpPosition[i] : nullptr);
      if (result != nullptr) {
        result->time[i] = t;
        result->tcpSpeed[i] = speed;
      }
      record(interval, speed, velocity);
    }
  }

  // Samples only the given intervals, each on its own grid, finer than the output grid so that the
  // output grid, shifted by the stretching, rarely finds anything new.
  void sampleIntervals(const Pchip& motion, double checkTimeStep, const std::vector<std::size_t>& intervals) {
    const auto& knots = motion.knots();
    for (const std::size_t k : intervals) {
      const double length = knots[k + 1] - knots[k];
      const auto steps = static_cast<std::size_t>(std::ceil(kLocalGridRefinement * length / checkTimeStep));
      for (std::size_t i = 0; i <= steps; ++i) {
        const double t = knots[k] + length * static_cast<double>(i) / static_cast<double>(steps);
        motion.evaluateInInterval(k, t, position_, velocity_, acceleration_);
        record(k, tcpSpeed(position_, velocity_, nullptr), velocity_);
      }
    }
  }

  double worstRatio() const { return worstRatio_; }
  bool withinLimits() const { return worstRatio_ <= 1.0; }

  // Stretches the offending intervals and returns the intervals whose shape changed (the
  // stretched ones and their neighbours, whose end slopes depend on them); resets the check.
  std::vector<std::size_t> stretchOffendingIntervals(std::vector<double>& duration) {
    std::vector<std::size_t> changed;
    for (std::size_t k = 0; k < duration.size(); ++k) {
      const bool stretched = stretch_[k] > 1.0;
      if (stretched) duration[k] *= stretch_[k];
      if (stretched || (k > 0 && stretch_[k - 1] > 1.0) || (k + 1 < duration.size() && stretch_[k + 1] > 1.0)) {
        changed.push_back(k);
      }
    }
    reset();
    return changed;
  }

  void reset() {
    std::fill(stretch_.begin(), stretch_.end(), 1.0);
    worstRatio_ = 0.0;
  }

private:
  double tcpSpeed(const robot::Vector6& q, const robot::Vector6& qd, Eigen::Vector3d* tcpPosition) {
    const int tip = model_.tipLink();
    robot::chainKinematics(model_, q, tip, kinematics_);
    if (tcpPosition != nullptr) *tcpPosition = kinematics_.linkPoses[tip].translation();
    robot::jacobian(model_, kinematics_, tip, jacobian_);
    return (jacobian_.topRows<3>() * qd).norm();
  }

  void record(std::size_t interval, double tcpSpeed, const robot::Vector6& qd) {
    const double ratio = std::max(tcpSpeed / maxTcpSpeed_, qd.cwiseAbs().cwiseQuotient(jointSpeedLimits_).maxCoeff());
    worstRatio_ = std::max(worstRatio_, ratio);
    if (ratio > 1.0) stretch_[interval] = std::max(stretch_[interval], ratio * (1.0 + kStretchMargin));
  }

  const robot::RobotModel& model_;
  robot::KinematicsData kinematics_;
  robot::Jacobian jacobian_;  // tcpSpeed's, allocated once
  double maxTcpSpeed_;
  robot::Vector6 jointSpeedLimits_;
  std::vector<double> stretch_;
  double worstRatio_ = 0.0;
  robot::Vector6 position_, velocity_, acceleration_;
};

// The steps before the PCHIP check: the dense path and its planned profile.
struct Plan {
  robot::Vector6 jointSpeedLimits;
  double acceleration = 0.0;
  DensePath dense;
  PlannedProfile profile;
};

Plan planOf(const robot::RobotModel& model, const JointPath& path, const TimeScalingOptions& options) {
  validateOptions(options);
  validateJointPath(model, path, "time scaling: path");
  Plan plan;
  plan.jointSpeedLimits = jointSpeedLimitsOf(model);
  plan.acceleration = options.maxTcpAcceleration.value_or(options.maxTcpSpeed / options.riseTime);
  DensificationOptions densification{options.maxJointStep, options.maxTcpStep, options.smoothWaypointSpacing};
  plan.dense = densifyJointPath(model, path, densification);
  if (plan.dense.waypoints.size() == 2) {  // a profile from rest to rest needs an interior waypoint
    densification.maxJointStep = 0.5 * (plan.dense.waypoints[1] - plan.dense.waypoints[0]).cwiseAbs().maxCoeff();
    plan.dense = densifyJointPath(model, path, densification);
  }
  plan.profile = planProfile(plan.dense, plan.jointSpeedLimits, options.maxTcpSpeed * (1.0 - kPlanningHeadroom),
                             plan.acceleration);
  return plan;
}

}  // namespace

double plannedDuration(const robot::RobotModel& model, const JointPath& path, const TimeScalingOptions& options) {
  return planOf(model, path, options).profile.time.back();
}

namespace {

// scaleToTcpSpeed with the output grid's samples kept, or only checked (scaledDuration): the same computation.
TimedTrajectory scaled(const robot::RobotModel& model, const JointPath& path, const TimeScalingOptions& options,
                       bool keepSamples) {
  Plan plan = planOf(model, path, options);
  const robot::Vector6& jointSpeedLimits = plan.jointSpeedLimits;
  const double acceleration = plan.acceleration;
  DensePath& dense = plan.dense;
  const PlannedProfile& profile = plan.profile;

  TimedTrajectory result;
  placeKnots(dense, profile, options, result.knots, result.knotTimes);
  std::vector<double> duration = intervalDurations(result.knotTimes);
  const std::size_t knotCount = result.knots.size();
  Eigen::MatrixXd values(knotCount, 6);
  for (std::size_t k = 0; k < knotCount; ++k) values.row(k) = result.knots[k].transpose();

  result.tcpSpeedLimit = options.maxTcpSpeed;
  result.jointSpeedLimits = jointSpeedLimits;
  LimitCheck check(model, options, jointSpeedLimits, duration.size());
  Pchip motion;
  const auto refit = [&] {
    cumulativeTimes(duration, result.knotTimes);
    motion.fit(result.knotTimes, values, PchipEnds::ZeroSlope);
  };
  refit();

  // Stretches the given intervals until they pass on their own fine grids; after too many rounds
  // scales the whole timing instead. Only those intervals are sampled, so only their slopes are refitted
  // (Pchip::refitAround: the same interpolant there; a whole refit each round was a quarter of the scaling,
  // where an overshoot creeps back one interval per round for all 25 rounds).
  const auto settle = [&](std::vector<std::size_t> intervals) {
    for (int round = 0; !intervals.empty(); ++round) {
      cumulativeTimes(duration, result.knotTimes);
      motion.refitAround(result.knotTimes, intervals, PchipEnds::ZeroSlope);
      check.reset();
      check.sampleIntervals(motion, options.checkTimeStep, intervals);
      if (check.withinLimits()) return;
      if (round == kLocalRounds) {
        for (double& d : duration) d *= check.worstRatio() * (1.0 + kStretchMargin);
        return;
      }
      intervals = check.stretchOffendingIntervals(duration);
    }
  };
  // Where the planned acceleration jumps (ramp ends) PCHIP overshoots by a few 0.1 %: those
  // intervals are settled first, so the output grid is usually sampled only once.
  settle(intervalsAtProfileCorners(profile, result.knotTimes, acceleration));
  for (int fullPass = 0;; ++fullPass) {
    refit();
    check.reset();
    check.sampleAll(motion, options.checkTimeStep, keepSamples ? &result : nullptr);
    if (check.withinLimits()) break;
    if (fullPass >= kLocalRounds) {
      const double factor = check.worstRatio() * (1.0 + kStretchMargin * (fullPass - kLocalRounds + 1));
      for (double& d : duration) d *= factor;
      continue;
    }
    settle(check.stretchOffendingIntervals(duration));
  }

  result.tcpPathLength = dense.tcpArcLength.back();
  result.densePath = std::move(dense.waypoints);
  return result;
}

}  // namespace

TimedTrajectory scaleToTcpSpeed(const robot::RobotModel& model, const JointPath& path,
                                const TimeScalingOptions& options) {
  return scaled(model, path, options, true);
}

double scaledDuration(const robot::RobotModel& model, const JointPath& path, const TimeScalingOptions& options) {
  return scaled(model, path, options, false).duration();
}

}  // namespace arcplan::trajectory
