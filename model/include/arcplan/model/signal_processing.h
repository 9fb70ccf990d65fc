#pragma once
// Deriving velocities and accelerations a log does not contain, without shifting them in time.
//
// Method (documented in docs/model.md): the samples are linearly resampled onto a uniform grid at
// the median sampling step (robot logs have jittery steps; a coarser step only when a gap would make
// the grid over 4x longer than the log), low-pass filtered with a second-order
// Butterworth filter run forwards and backwards (zero phase, effective fourth order, cut-off
// `cutoffHz`), differentiated with central differences, and interpolated back onto the original
// sample times. The ends are padded with an odd reflection so the filter starts settled.
#include <Eigen/Core>

namespace arcplan::model {

// Forward–backward second-order Butterworth low-pass of uniformly sampled values (each column).
// Cut-offs at or above 0.45·sampleRate leave the signal unfiltered.
Eigen::MatrixXd zeroPhaseLowPass(const Eigen::MatrixXd& values, double sampleRate, double cutoffHz);

// d/dt of every column of `values` sampled at strictly increasing `time`, by the method above.
Eigen::MatrixXd smoothDerivative(const Eigen::VectorXd& time, const Eigen::MatrixXd& values, double cutoffHz);

// Linear interpolation of every column at `at` (clamped to the first/last sample outside).
Eigen::MatrixXd interpolateLinear(const Eigen::VectorXd& time, const Eigen::MatrixXd& values,
                                  const Eigen::VectorXd& at);

}  // namespace arcplan::model
