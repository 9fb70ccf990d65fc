#pragma once
// arcplan's own synthetic UR10e logs: a joint trajectory (an excitation trajectory, or any planned
// and time-scaled one read from CSV), the controller's rigid-body torque as target_moment, and the
// measured channel (motor currents or actual joint positions) produced by a "true" model with
// chosen effects and parameters plus Gaussian noise. Used for tests with hidden effects and demos.
#include <filesystem>

#include <Eigen/Core>

#include "arcplan/model/measurements.h"
#include "arcplan/model/model_spec.h"

namespace arcplan::model {

struct Trajectory {
  Eigen::VectorXd time;
  Eigen::MatrixXd q, qd, qdd;  // samples x joints
};

// A periodic Fourier-series excitation (Swevers et al.), the kind of trajectory recorded in the
// real UR10e identification logs: q_j(t) = q0_j + Σ_l a_jl/(ω_l)·sin(ω_l t) - b_jl/(ω_l)·cos(ω_l t),
// ω_l = 2π·l·baseFrequency, random coefficients from `seed`, scaled so that every joint stays
// within `amplitude` of its centre, `maxSpeed` and `maxAcceleration`. Not collision-checked.
struct ExcitationOptions {
  double duration = 60.0;  // s
  double rate = 500.0;     // Hz (UR e-Series RTDE runs at 500 Hz)
  int harmonics = 5;
  double baseFrequency = 0.1;    // Hz: a 10 s period
  double amplitude = 1.2;        // rad about the centre
  double maxSpeed = 0.8;         // rad/s
  double maxAcceleration = 3.0;  // rad/s²
  unsigned seed = 1;
};
Trajectory excitationTrajectory(const Eigen::VectorXd& center, const ExcitationOptions& options);

// A planned trajectory from CSV with a header: a time column (t, time or timestamp) and one
// position column per joint (q0.., q_0.., or target_q_0..), resampled at `rate` with velocities and
// accelerations by the zero-phase derivative of signal_processing.h.
Trajectory readTrajectory(const std::filesystem::path& file, double rate, double cutoffHz);

struct SimulationOptions {
  double noise = -1.0;  // standard deviation of the measured channel; < 0: 0.05 A (currents), 2e-5 rad (positions)
  unsigned seed = 1;
  double temperatureStart = 30.0;  // °C, joint j starts at temperatureStart + j
  double temperatureRise = 15.0;   // °C over the log
};

// The log a robot following `trajectory` would record if `truth` (with its stored parameters, or
// typical UR10e values where it has none) were exact: timestamp, target_q/qd/qdd, target_moment,
// actual_q/qd, joint_temperatures, and actual_current (joint_current) or a lagging actual_q
// (joint_tracking). Throws arcplan::Error for gearbox_ftd models or a joint count that differs from
// the robot's.
Log simulateLog(const ModelSpec& truth, const Trajectory& trajectory, const SimulationOptions& options);

}  // namespace arcplan::model
