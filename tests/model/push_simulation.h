#pragma once
// Simulated pushes for the event tests: a force at the tool, seen by the joints as Jᵀf and by the
// motor currents through each joint's current per N·m, added to a log's measured currents in known
// windows. The Jacobian comes from arcplan's kinematics (tested against finite differences of
// forward kinematics in robot_tests), the gains from the test's own regression.
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Dense>

#include "arcplan/model/measurements.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/robot_model.h"

namespace arcplan::testing {

struct Push {
  double start = 0.0, end = 0.0;                    // s
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N, base frame, at full strength
};

// Trapezoid: the force rises and falls over `ramp` (at most a fifth of the push), a person's push.
inline double pushStrength(const Push& push, double t) {
  if (t <= push.start || t >= push.end) return 0.0;
  const double ramp = std::min(0.1, 0.2 * (push.end - push.start));
  return std::min({1.0, (t - push.start) / ramp, (push.end - t) / ramp});
}

// `count` pushes of 20–60 N for 0.3–2 s in random directions, at random times at least `gap` s apart
// and away from the log's ends (seeded).
inline std::vector<Push> randomPushes(const model::Log& log, int count, unsigned seed, double gap = 3.0) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> magnitude(20.0, 60.0), duration(0.3, 2.0), unit(0.0, 1.0);
  std::normal_distribution<double> gaussian;
  const double first = log.time[0] + 5.0, last = log.time[log.time.size() - 1] - 5.0;
  std::vector<Push> pushes;
  for (int attempt = 0; attempt < 1000 && static_cast<int>(pushes.size()) < count; ++attempt) {
    Push push;
    push.start = first + unit(random) * (last - first - 2.0);
    push.end = push.start + duration(random);
    const Eigen::Vector3d direction(gaussian(random), gaussian(random), gaussian(random));
    push.force = magnitude(random) * direction.normalized();
    const bool apart = std::all_of(pushes.begin(), pushes.end(), [&](const Push& other) {
      return push.end + gap < other.start || other.end + gap < push.start;
    });
    if (apart) pushes.push_back(push);
  }
  std::sort(pushes.begin(), pushes.end(), [](const Push& a, const Push& b) { return a.start < b.start; });
  return pushes;
}

// Adds gain_j · (Jᵀf)_j to the log's actual_current_j at every sample of every push.
inline void addPushes(model::Log& log, const robot::RobotModel& robot, const std::vector<Push>& pushes,
                      const Eigen::VectorXd& gains) {
  auto& current = log.vectors.at("actual_current");
  const auto& q = log.vectors.at("actual_q");
  robot::KinematicsData kinematics(robot);
  for (Eigen::Index k = 0; k < log.time.size(); ++k) {
    for (const auto& push : pushes) {
      const double strength = pushStrength(push, log.time[k]);
      if (strength == 0.0) continue;
      robot::forwardKinematics(robot, q.row(k).transpose(), kinematics);
      const Eigen::VectorXd torque = robot::jacobian(robot, kinematics).topRows(3).transpose() * push.force;
      current.row(k) += (strength * gains.array() * torque.array()).matrix().transpose();
    }
  }
}

// Current per N·m of each joint by plain least squares of actual_current on target_moment, an offset
// and sgn(qd) (the test's own regression, independent of arcplan's fitting).
inline Eigen::VectorXd currentPerTorque(const model::Log& log) {
  const auto& current = log.vectors.at("actual_current");
  const auto& moment = log.vectors.at("target_moment");
  const auto& qd = log.vectors.at("actual_qd");
  Eigen::VectorXd gains(current.cols());
  for (Eigen::Index j = 0; j < current.cols(); ++j) {
    Eigen::MatrixXd x(current.rows(), 3);
    x.col(0) = moment.col(j);
    x.col(1).setOnes();
    x.col(2) = qd.col(j).array().tanh();  // tanh(qd / 1 rad/s): a smooth direction
    gains[j] = x.colPivHouseholderQr().solve(current.col(j))[0];
  }
  return gains;
}

}  // namespace arcplan::testing
