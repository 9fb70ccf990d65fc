#pragma once
// Synthetic logs for the model tests, written from closed-form motions (independent of the
// simulator under test).
#include <cmath>

#include "arcplan/model/measurements.h"

namespace arcplan::testing {

// Six joints moving on sums of two sines (exact q, qd and qdd), a smooth made-up load torque, a
// warming temperature ramp, and zero currents to be filled in by the test.
struct MotionLog {
  model::Log log;
  Eigen::MatrixXd qdd;  // exact accelerations (the log itself has none)
};

inline MotionLog makeMotionLog(int samples, double rate, double phase = 0.0) {
  MotionLog motion;
  auto& log = motion.log;
  log.source = "synthetic";
  log.time = Eigen::VectorXd::LinSpaced(samples, 0.0, (samples - 1) / rate);
  Eigen::MatrixXd q(samples, 6), qd(samples, 6), tau(samples, 6), temperature(samples, 6);
  motion.qdd.resize(samples, 6);
  for (int j = 0; j < 6; ++j) {
    const double w1 = 0.9 + 0.23 * j, w2 = 2.1 + 0.17 * j, a1 = 0.9, a2 = 0.25;
    for (int k = 0; k < samples; ++k) {
      const double t = log.time[k] + phase;
      q(k, j) = a1 * std::sin(w1 * t) + a2 * std::sin(w2 * t + j) - 0.5;
      qd(k, j) = a1 * w1 * std::cos(w1 * t) + a2 * w2 * std::cos(w2 * t + j);
      motion.qdd(k, j) = -a1 * w1 * w1 * std::sin(w1 * t) - a2 * w2 * w2 * std::sin(w2 * t + j);
      tau(k, j) = (10.0 + 5.0 * j) * std::cos(q(k, j)) + 2.0 * motion.qdd(k, j);
      temperature(k, j) = 30.0 + j + 15.0 * k / samples;
    }
  }
  log.vectors["actual_q"] = q;
  log.vectors["actual_qd"] = qd;
  log.vectors["target_moment"] = tau;
  log.vectors["joint_temperatures"] = temperature;
  log.vectors["actual_current"] = Eigen::MatrixXd::Zero(samples, 6);
  log.quality.dataRows = log.quality.keptRows = static_cast<std::size_t>(samples);
  return motion;
}

}  // namespace arcplan::testing
