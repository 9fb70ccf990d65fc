#include "arcplan/model/signal_processing.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace arcplan::model {
namespace {

// Second-order Butterworth low-pass by the bilinear transform with pre-warping. Hand-written: the
// Debian libraries arcplan uses have no IIR filter design, and this is a handful of coefficients.
struct Biquad {
  double b0, b1, b2, a1, a2;
};

Biquad butterworthLowPass(double sampleRate, double cutoffHz) {
  const double k = std::tan(M_PI * cutoffHz / sampleRate);
  const double norm = 1.0 / (1.0 + std::sqrt(2.0) * k + k * k);
  Biquad f;
  f.b0 = k * k * norm;
  f.b1 = 2.0 * f.b0;
  f.b2 = f.b0;
  f.a1 = 2.0 * (k * k - 1.0) * norm;
  f.a2 = (1.0 - std::sqrt(2.0) * k + k * k) * norm;
  return f;
}

// Direct form II transposed, started in the steady state of its first input (unit DC gain).
void runFilter(const Biquad& f, std::vector<double>& x) {
  if (x.empty()) return;
  const double first = x.front();
  double z2 = (f.b2 - f.a2) * first;
  double z1 = (f.b1 - f.a1) * first + z2;
  for (double& value : x) {
    const double input = value;
    const double output = f.b0 * input + z1;
    z1 = f.b1 * input - f.a1 * output + z2;
    z2 = f.b2 * input - f.a2 * output;
    value = output;
  }
}

void filterForwardBackward(const Biquad& f, const double* in, double* out, Eigen::Index n, Eigen::Index pad) {
  std::vector<double> work;
  work.reserve(static_cast<std::size_t>(n + 2 * pad));
  for (Eigen::Index i = pad; i >= 1; --i) work.push_back(2.0 * in[0] - in[i]);
  for (Eigen::Index i = 0; i < n; ++i) work.push_back(in[i]);
  for (Eigen::Index i = 1; i <= pad; ++i) work.push_back(2.0 * in[n - 1] - in[n - 1 - i]);
  runFilter(f, work);
  std::reverse(work.begin(), work.end());
  runFilter(f, work);
  std::reverse(work.begin(), work.end());
  for (Eigen::Index i = 0; i < n; ++i) out[i] = work[static_cast<std::size_t>(pad + i)];
}

Eigen::MatrixXd centralDifference(const Eigen::MatrixXd& values, double step) {
  const Eigen::Index n = values.rows();
  Eigen::MatrixXd derivative(n, values.cols());
  if (n < 2) return Eigen::MatrixXd::Zero(n, values.cols());
  if (n == 2) {
    derivative.row(0) = derivative.row(1) = (values.row(1) - values.row(0)) / step;
    return derivative;
  }
  derivative.middleRows(1, n - 2) = (values.bottomRows(n - 2) - values.topRows(n - 2)) / (2.0 * step);
  derivative.row(0) = (-3.0 * values.row(0) + 4.0 * values.row(1) - values.row(2)) / (2.0 * step);
  derivative.row(n - 1) = (3.0 * values.row(n - 1) - 4.0 * values.row(n - 2) + values.row(n - 3)) / (2.0 * step);
  return derivative;
}

}  // namespace

Eigen::MatrixXd zeroPhaseLowPass(const Eigen::MatrixXd& values, double sampleRate, double cutoffHz) {
  const Eigen::Index n = values.rows();
  if (n < 4 || cutoffHz <= 0.0 || cutoffHz >= 0.45 * sampleRate) return values;
  const Biquad filter = butterworthLowPass(sampleRate, cutoffHz);
  // Pad about two time constants of the filter so the reflected start has settled.
  const Eigen::Index pad =
      std::min<Eigen::Index>(n - 1, std::max<Eigen::Index>(9, std::lround(2.0 * sampleRate / cutoffHz)));
  Eigen::MatrixXd filtered(n, values.cols());
  for (Eigen::Index c = 0; c < values.cols(); ++c) {
    filterForwardBackward(filter, values.col(c).data(), filtered.col(c).data(), n, pad);
  }
  return filtered;
}

Eigen::MatrixXd interpolateLinear(const Eigen::VectorXd& time, const Eigen::MatrixXd& values,
                                  const Eigen::VectorXd& at) {
  const Eigen::Index n = time.size();
  Eigen::MatrixXd result(at.size(), values.cols());
  Eigen::Index segment = 0;
  for (Eigen::Index i = 0; i < at.size(); ++i) {
    const double t = at[i];
    if (n == 1 || t <= time[0]) {
      result.row(i) = values.row(0);
      continue;
    }
    if (t >= time[n - 1]) {
      result.row(i) = values.row(n - 1);
      continue;
    }
    // `at` is usually increasing: walk forward from the last segment, else search.
    if (segment >= n - 1 || time[segment] > t) {
      segment = static_cast<Eigen::Index>(std::upper_bound(time.data(), time.data() + n, t) - time.data()) - 1;
    }
    while (time[segment + 1] < t) ++segment;
    const double w = (t - time[segment]) / (time[segment + 1] - time[segment]);
    result.row(i) = (1.0 - w) * values.row(segment) + w * values.row(segment + 1);
  }
  return result;
}

Eigen::MatrixXd smoothDerivative(const Eigen::VectorXd& time, const Eigen::MatrixXd& values, double cutoffHz) {
  const Eigen::Index n = time.size();
  if (n < 2) return Eigen::MatrixXd::Zero(n, values.cols());
  std::vector<double> steps(static_cast<std::size_t>(n - 1));
  for (Eigen::Index i = 0; i + 1 < n; ++i) steps[static_cast<std::size_t>(i)] = time[i + 1] - time[i];
  std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2), steps.end());
  // The median step, unless a gap in the log would make the grid more than 4x longer than the log.
  const double step = std::max(steps[steps.size() / 2], (time[n - 1] - time[0]) / (4.0 * static_cast<double>(n)));
  const auto gridSize = static_cast<Eigen::Index>(std::floor((time[n - 1] - time[0]) / step + 1e-9)) + 1;
  const Eigen::VectorXd grid =
      Eigen::VectorXd::LinSpaced(gridSize, time[0], time[0] + step * static_cast<double>(gridSize - 1));
  const Eigen::MatrixXd uniform = interpolateLinear(time, values, grid);
  const Eigen::MatrixXd derivative = centralDifference(zeroPhaseLowPass(uniform, 1.0 / step, cutoffHz), step);
  return interpolateLinear(grid, derivative, time);
}

}  // namespace arcplan::model
