#pragma once
// Synthetic logs for the model tests: closed-form motions (independent of the simulator under
// test), a joint driven along a given path, pairs of simulated fit / validation logs for the
// hidden-effect cases, and what an effect's regressor makes of a dataset.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "arcplan/model/dataset.h"
#include "arcplan/model/effect.h"
#include "arcplan/model/measurements.h"
#include "arcplan/model/model_spec.h"
#include "arcplan/model/simulate.h"

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

// A joint_current model (load torque: target_moment) with `effects`, the inside of the YAML list of
// a model file ("drive_gain, {id: coulomb}"; empty for none), parsed as the file m.yaml.
inline model::ModelSpec jointCurrentModel(const std::string& effects = "") {
  return model::parseModelYaml("kind: joint_current\nload_torque: target_moment\neffects: [" + effects + "]\n",
                               "m.yaml");
}

// makeMotionLog at 100 Hz, `samples` long, with joint 0 following `path` (rad) and then resting at its
// last value: a dataset of a joint_current model without effects.
inline model::Dataset pathDataset(const std::vector<double>& path, int samples) {
  auto motion = makeMotionLog(samples, 100.0);
  Eigen::MatrixXd& q = motion.log.vectors["actual_q"];
  for (int k = 0; k < samples; ++k) q(k, 0) = path[std::min<std::size_t>(static_cast<std::size_t>(k), path.size() - 1)];
  return model::makeJointDataset(motion.log, jointCurrentModel());
}

// The regressor columns (one per parameter) of `spec`'s effect on channel `channel` of `data`, with
// the nonlinear parameter `nonlinear` (a rate, a delay) where the effect has one.
inline Eigen::MatrixXd regressorColumns(const model::EffectSpec& spec, const model::Dataset& data, int channel = 0,
                                        double nonlinear = 0.0) {
  const auto effect = model::createEffect(spec);
  Eigen::MatrixXd columns(data.samples(channel), static_cast<Eigen::Index>(effect->parameterNames().size()));
  effect->regressor(data, channel, nonlinear, columns);
  return columns;
}

// The same for the effect registered as `id`, with its default options.
inline Eigen::MatrixXd regressorColumns(const std::string& id, const model::Dataset& data, int channel = 0,
                                        double nonlinear = 0.0) {
  model::EffectSpec spec;
  spec.id = id;
  return regressorColumns(spec, data, channel, nonlinear);
}

// A fit and a validation log simulated from `truth` along two excitation trajectories (seeds
// `seed` and `seed + 1`, 20 s at 250 Hz: fast enough for the suite; the 60 s, 500 Hz case is the
// speed benchmark in perf/), prepared as datasets for the model `base`.
struct SimulatedPair {
  model::Dataset data, validation;
};

inline SimulatedPair simulatePair(const model::ModelSpec& truth, const model::ModelSpec& base, double noise,
                                  unsigned seed = 11) {
  model::ExcitationOptions excitation;
  excitation.duration = 20.0;
  excitation.rate = 250.0;
  Eigen::VectorXd center(6);
  center << 0.0, -M_PI / 2, M_PI / 4, -M_PI / 2, -M_PI / 2, 0.0;
  model::SimulationOptions simulation;
  simulation.noise = noise;
  auto simulate = [&](unsigned s) {
    excitation.seed = s;
    simulation.seed = s;
    return model::makeJointDataset(
        model::simulateLog(truth, model::excitationTrajectory(center, excitation), simulation), base);
  };
  return {simulate(seed), simulate(seed + 1)};
}

}  // namespace arcplan::testing
