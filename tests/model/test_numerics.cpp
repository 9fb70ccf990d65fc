// Zero-phase derivatives and the least-squares core, against closed forms and a second solver.
#include <cmath>
#include <random>

#include <Eigen/LU>
#include <Eigen/QR>
#include <gtest/gtest.h>

#include "arcplan/model/least_squares.h"
#include "arcplan/model/signal_processing.h"

namespace {

using arcplan::model::NormalEquations;
using arcplan::model::solveLeastSquares;

TEST(SignalProcessing, DerivativeOfASineOnJitteryTimesMatchesTheCosine) {
  // ~100 Hz with ±2 ms jitter, like the real UR10e logs.
  std::mt19937 random(5);
  std::uniform_real_distribution<double> jitter(-0.002, 0.002);
  const int n = 3000;
  Eigen::VectorXd time(n);
  for (int i = 0; i < n; ++i) time[i] = 0.01 * i + jitter(random);
  const double w = 2.0 * M_PI * 0.7;
  Eigen::MatrixXd values(n, 1);
  for (int i = 0; i < n; ++i) values(i, 0) = std::sin(w * time[i]);
  const Eigen::MatrixXd derivative = arcplan::model::smoothDerivative(time, values, 10.0);
  double worst = 0.0;
  for (int i = 100; i < n - 100; ++i) worst = std::max(worst, std::abs(derivative(i, 0) - w * std::cos(w * time[i])));
  EXPECT_LT(worst, 0.01 * w);  // 1 % of the amplitude; a phase lag of 1 sample would be 4 %
}

TEST(SignalProcessing, ForwardBackwardButterworthHasZeroPhaseAndHalfAmplitudeAtCutoff) {
  // |H(fc)|² = 1/2 for a Butterworth filter, so forward + backward gives exactly 1/2 at the cut-off
  // (bilinear transform with pre-warping keeps fc exact), and no phase shift at any frequency.
  const double rate = 500.0, cutoff = 20.0;
  const int n = 20000;
  Eigen::MatrixXd values(n, 2);
  for (int i = 0; i < n; ++i) {
    const double t = i / rate;
    values(i, 0) = std::sin(2.0 * M_PI * cutoff * t);
    values(i, 1) = std::sin(2.0 * M_PI * 2.0 * t);
  }
  const Eigen::MatrixXd filtered = arcplan::model::zeroPhaseLowPass(values, rate, cutoff);
  // Amplitude and phase by projection on sin/cos over the middle of the record.
  for (int c = 0; c < 2; ++c) {
    const double f = c == 0 ? cutoff : 2.0;
    double s = 0.0, k = 0.0;
    for (int i = 5000; i < 15000; ++i) {
      s += filtered(i, c) * std::sin(2.0 * M_PI * f * i / rate);
      k += filtered(i, c) * std::cos(2.0 * M_PI * f * i / rate);
    }
    s *= 2.0 / 10000.0;
    k *= 2.0 / 10000.0;
    const double expected = 1.0 / (1.0 + std::pow(f / cutoff, 4));
    EXPECT_NEAR(std::hypot(s, k), expected, 2e-3) << "f = " << f;
    EXPECT_NEAR(std::atan2(k, s), 0.0, 2e-3) << "f = " << f;
  }
}

TEST(LeastSquares, AgreesWithHouseholderQrAndTheTextbookStandardErrors) {
  std::mt19937 random(7);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  const int n = 500, p = 4;
  Eigen::MatrixXd x(n, p);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < p; ++k) x(i, k) = gaussian(random) * (k + 1) * 100.0;  // different scales
    y[i] = 3.0 * x(i, 0) - 0.01 * x(i, 2) + 0.5 + 0.1 * gaussian(random);
  }
  const auto solution = solveLeastSquares(NormalEquations::of(x, y));
  const Eigen::VectorXd reference = x.householderQr().solve(y);
  EXPECT_LT((solution.coefficients - reference).cwiseAbs().maxCoeff(), 1e-9);
  const Eigen::VectorXd residual = y - x * reference;
  EXPECT_NEAR(solution.residualSquares, residual.squaredNorm(), 1e-8 * residual.squaredNorm());
  const Eigen::MatrixXd covariance = residual.squaredNorm() / (n - p) * (x.transpose() * x).inverse();
  for (int k = 0; k < p; ++k)
    EXPECT_NEAR(solution.standardErrors[k], std::sqrt(covariance(k, k)), 1e-9 * std::sqrt(covariance(k, k)));
  EXPECT_EQ(solution.rank, p);
}

TEST(LeastSquares, DropsACollinearColumnAndKeepsTheFirst) {
  const int n = 200;
  Eigen::MatrixXd x(n, 3);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    x(i, 0) = 1.0;
    x(i, 1) = std::sin(0.1 * i);
    x(i, 2) = 2.0 * x(i, 1) - 3.0;  // a combination of the first two
    y[i] = 1.0 + 4.0 * x(i, 1);
  }
  const auto solution = solveLeastSquares(NormalEquations::of(x, y));
  EXPECT_EQ(solution.rank, 2);
  EXPECT_TRUE(solution.identifiable[0] && solution.identifiable[1]);
  EXPECT_FALSE(solution.identifiable[2]);
  EXPECT_TRUE(std::isnan(solution.standardErrors[2]));
  EXPECT_NEAR(solution.coefficients[0], 1.0, 1e-10);
  EXPECT_NEAR(solution.coefficients[1], 4.0, 1e-10);
  EXPECT_EQ(solution.coefficients[2], 0.0);
}

TEST(LeastSquares, FoldEquationsByDifferenceEqualAFitOnTheOtherFolds) {
  std::mt19937 random(8);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  Eigen::MatrixXd x(300, 2);
  Eigen::VectorXd y(300);
  for (int i = 0; i < 300; ++i) {
    x(i, 0) = 1.0;
    x(i, 1) = gaussian(random);
    y[i] = 2.0 - x(i, 1) + gaussian(random);
  }
  const auto all = NormalEquations::of(x, y);
  const auto fold = NormalEquations::of(x.topRows(100), y.head(100));
  const auto rest = solveLeastSquares(all - fold);
  const Eigen::VectorXd direct = x.bottomRows(200).householderQr().solve(y.tail(200));
  EXPECT_LT((rest.coefficients - direct).cwiseAbs().maxCoeff(), 1e-10);
  const double heldOut = (y.head(100) - x.topRows(100) * direct).squaredNorm();
  EXPECT_NEAR(fold.residualSquares(rest.coefficients), heldOut, 1e-9 * heldOut);
}

}  // namespace
