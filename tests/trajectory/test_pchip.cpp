// PCHIP against hand-computed Fritsch–Butland slopes, SciPy's PchipInterpolator (values computed
// once with scipy 1.10 and written here), and the shape properties: exact at knots, C¹, monotone
// where the data is, no overshoot.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/trajectory/pchip.h"

namespace arcplan::trajectory {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Knots and two columns chosen to exercise every slope rule: a weighted harmonic mean (column 0,
// knots 1-3), flat secants and a sign change (column 1 interior: slope 0), the end slope reset to 0
// (column 0 at x = 5) and the end slope limited to 3·secant (column 1 at x = 5).
const std::vector<double> kKnots{0.0, 1.0, 2.5, 3.0, 5.0};
MatrixXd sampleValues() {
  MatrixXd values(5, 2);
  values << 0.0, 1.0, 1.0, 0.5, 1.2, 0.5, 3.0, -1.0, 3.5, 2.0;
  return values;
}

TEST(Pchip, SlopesMatchHandComputedFritschButlandRules) {
  const Pchip pchip(kKnots, sampleValues());
  const MatrixXd& d = pchip.slopes();
  // Column 0, knot 1: h = 1, 1.5; secants 1 and 0.2/1.5. Weights 2·1.5+1 = 4 and 1.5+2·1 = 3.5.
  EXPECT_NEAR(d(1, 0), 7.5 / (4.0 / 1.0 + 3.5 / (0.2 / 1.5)), 1e-12);
  // Knot 2: h = 1.5, 0.5; secants 0.2/1.5 and 3.6; weights 2·0.5+1.5 = 2.5 and 0.5+3 = 3.5.
  EXPECT_NEAR(d(2, 0), 6.0 / (2.5 / (0.2 / 1.5) + 3.5 / 3.6), 1e-12);
  // Start: ((2·1 + 1.5)·1 − 1·0.1333)/2.5, same sign as the first secant.
  EXPECT_NEAR(d(0, 0), (3.5 * 1.0 - 0.2 / 1.5) / 2.5, 1e-12);
  // End: ((2·2 + 0.5)·0.25 − 2·3.6)/2.5 < 0 has the wrong sign: 0.
  EXPECT_EQ(d(4, 0), 0.0);
  // Column 1: secants −0.5, 0, −3, 1.5: every interior knot is flat or an extremum.
  EXPECT_EQ(d(1, 1), 0.0);
  EXPECT_EQ(d(2, 1), 0.0);
  EXPECT_EQ(d(3, 1), 0.0);
  EXPECT_NEAR(d(0, 1), (3.5 * -0.5 - 1.0 * 0.0) / 2.5, 1e-12);
  // End: ((4.5)·1.5 − 2·(−3))/2.5 = 5.1 > 3·1.5 while the secants change sign: limited to 4.5.
  EXPECT_NEAR(d(4, 1), 4.5, 1e-12);
}

TEST(Pchip, MatchesScipyPchipInterpolator) {
  const Pchip pchip(kKnots, sampleValues());
  struct Reference {
    double t;
    double value[2], first[2], second[2];
  };
  // scipy.interpolate.PchipInterpolator(x, y)(t, nu) for nu = 0, 1, 2.
  const Reference references[] = {
      {0.4, {0.52211835, 0.7232}, {1.19906116, -0.636}, {-0.85549311, 0.52}},
      {1.7, {1.08637839, 0.5}, {0.06103545, 0.0}, {-0.00053803, 0.0}},
      {2.8, {2.3402481, -0.472}, {5.01872336, -4.32}, {-7.07205953, 7.2}},
      {4.1, {3.41345991, -0.500875}, {0.20568396, 1.36125}, {-0.27311321, 2.475}},
  };
  VectorXd value(2), first(2), second(2);
  for (const auto& reference : references) {
    pchip.evaluate(reference.t, value, first, second);
    for (int c = 0; c < 2; ++c) {
      EXPECT_NEAR(value[c], reference.value[c], 1e-7) << "t = " << reference.t;
      EXPECT_NEAR(first[c], reference.first[c], 1e-7) << "t = " << reference.t;
      EXPECT_NEAR(second[c], reference.second[c], 1e-7) << "t = " << reference.t;
    }
  }
}

TEST(Pchip, HandComputedHermiteValueOnAFlatStep) {
  // Knots 0..3, values 0, 1, 1, 2: secants 1, 0, 1, so the interior slopes are 0 and the start
  // slope is (3·1 − 1·0)/2 = 1.5. At t = 0.5 the Hermite basis is (0.5, 0.125, 0.5, −0.125):
  // 0.125·1.5 + 0.5·1 = 0.6875.
  MatrixXd values(4, 1);
  values << 0.0, 1.0, 1.0, 2.0;
  const Pchip pchip({0.0, 1.0, 2.0, 3.0}, values);
  VectorXd value(1);
  pchip.evaluate(0.5, value);
  EXPECT_NEAR(value[0], 0.6875, 1e-15);
  pchip.evaluate(1.5, value);  // the flat interval stays flat
  EXPECT_NEAR(value[0], 1.0, 1e-15);
}

TEST(Pchip, ExactAtKnotsAndContinuouslyDifferentiable) {
  const Pchip pchip(kKnots, sampleValues());
  const MatrixXd values = sampleValues();
  VectorXd value(2), left(2), right(2), second(2), ignored(2);
  for (std::size_t k = 0; k < kKnots.size(); ++k) {
    pchip.evaluate(kKnots[k], value);
    EXPECT_NEAR((value - values.row(k).transpose()).norm(), 0.0, 1e-14) << "knot " << k;
  }
  for (std::size_t k = 1; k + 1 < kKnots.size(); ++k) {
    // Derivative of the cubic on each side of knot k, evaluated exactly at the knot.
    pchip.evaluateInInterval(k - 1, kKnots[k], ignored, left, second);
    pchip.evaluateInInterval(k, kKnots[k], ignored, right, second);
    EXPECT_NEAR((left - right).norm(), 0.0, 1e-12) << "knot " << k;
    EXPECT_NEAR((left - pchip.slopes().row(k).transpose()).norm(), 0.0, 1e-12);
  }
}

TEST(Pchip, MonotoneDataStaysMonotoneWithoutOvershoot) {
  // A sharp step with uneven spacing: a cubic spline rings here, PCHIP must not.
  const std::vector<double> knots{0.0, 0.3, 1.0, 1.1, 2.0, 4.0, 4.2};
  MatrixXd values(7, 2);
  values.col(0) << 0.0, 0.0, 0.1, 1.0, 1.0, 1.2, 5.0;      // non-decreasing
  values.col(1) << 3.0, 2.0, 1.9, -1.0, -1.0, -1.5, -1.6;  // non-increasing
  const Pchip pchip(knots, values);
  VectorXd value(2), first(2), second(2);
  VectorXd previous = values.row(0).transpose();
  for (int i = 0; i <= 4200; ++i) {
    const double t = 0.001 * i;
    pchip.evaluate(t, value, first, second);
    const std::size_t k = pchip.intervalOf(t);
    for (int c = 0; c < 2; ++c) {
      const double low = std::min(values(k, c), values(k + 1, c)), high = std::max(values(k, c), values(k + 1, c));
      ASSERT_GE(value[c], low - 1e-12) << "overshoot below the interval's data at t = " << t;
      ASSERT_LE(value[c], high + 1e-12) << "overshoot above the interval's data at t = " << t;
    }
    ASSERT_GE(first[0], -1e-12) << "t = " << t;
    ASSERT_LE(first[1], 1e-12) << "t = " << t;
    ASSERT_GE(value[0], previous[0] - 1e-12);
    ASSERT_LE(value[1], previous[1] + 1e-12);
    previous = value;
  }
}

TEST(Pchip, ReproducesLinearDataExactly) {
  const std::vector<double> knots{0.0, 0.5, 2.0, 2.25, 3.0};
  MatrixXd values(5, 1);
  for (int k = 0; k < 5; ++k) values(k, 0) = 2.0 - 3.0 * knots[k];
  const Pchip pchip(knots, values);
  VectorXd value(1), first(1), second(1);
  for (double t = 0.0; t <= 3.0; t += 0.01) {
    pchip.evaluate(t, value, first, second);
    EXPECT_NEAR(value[0], 2.0 - 3.0 * t, 1e-12);
    EXPECT_NEAR(first[0], -3.0, 1e-12);
    EXPECT_NEAR(second[0], 0.0, 1e-9);
  }
}

TEST(Pchip, ZeroSlopeEndsStartAndStopAtRest) {
  const Pchip pchip(kKnots, sampleValues(), PchipEnds::ZeroSlope);
  VectorXd value(2), first(2), second(2);
  pchip.evaluate(kKnots.front(), value, first, second);
  EXPECT_EQ(first.norm(), 0.0);
  pchip.evaluate(kKnots.back(), value, first, second);
  EXPECT_EQ(first.norm(), 0.0);
  // Interior slopes are unchanged by the end condition.
  const Pchip free(kKnots, sampleValues());
  EXPECT_EQ((pchip.slopes().middleRows(1, 3) - free.slopes().middleRows(1, 3)).norm(), 0.0);
}

TEST(Pchip, TwoKnotsGiveTheStraightLine) {
  MatrixXd values(2, 1);
  values << 1.0, 3.0;
  const Pchip pchip({1.0, 2.0}, values);
  VectorXd value(1);
  pchip.evaluate(1.25, value);
  EXPECT_NEAR(value[0], 1.5, 1e-15);
}

// A refit around a few intervals after the knots moved (some intervals stretched, all later knots shifted) gives, on
// those intervals, exactly the interpolant a whole fit on the moved knots gives: the same bits, both end rules.
TEST(Pchip, RefitAroundIntervalsEqualsTheWholeFitThere) {
  std::vector<double> knots;
  MatrixXd values(40, 3);
  for (int k = 0; k < 40; ++k) {
    knots.push_back(0.1 * k + 0.01 * std::sin(3.0 * k));
    values.row(k) << std::sin(0.3 * k), std::cos(0.17 * k) * k, (k % 7) - 0.5 * (k % 3);
  }
  for (const PchipEnds ends : {PchipEnds::ShapePreserving, PchipEnds::ZeroSlope}) {
    Pchip refitted(knots, values, ends);
    std::vector<double> moved = knots;
    const std::vector<std::size_t> intervals{0, 1, 17, 18, 19, 37, 38};
    for (const std::size_t stretched : {1, 18, 38}) {
      const double extra = 0.03 * static_cast<double>(stretched % 5 + 1);
      for (std::size_t k = stretched + 1; k < moved.size(); ++k) moved[k] += extra;
    }
    refitted.refitAround(moved, intervals, ends);
    const Pchip whole(moved, values, ends);
    VectorXd a(3), b(3), da(3), db(3), dda(3), ddb(3);
    for (const std::size_t k : intervals) {
      for (int i = 0; i <= 10; ++i) {
        const double t = moved[k] + (moved[k + 1] - moved[k]) * i / 10.0;
        refitted.evaluateInInterval(k, t, a, da, dda);
        whole.evaluateInInterval(k, t, b, db, ddb);
        ASSERT_EQ(a, b) << "interval " << k;
        ASSERT_EQ(da, db) << "interval " << k;
        ASSERT_EQ(dda, ddb) << "interval " << k;
      }
    }
  }
  // Refused (other knot count, no such interval, knots not increasing) with the fit left as it was.
  Pchip pchip(knots, values);
  std::vector<double> decreasing = knots;
  decreasing[20] = decreasing[18];
  EXPECT_THROW(pchip.refitAround(std::vector<double>(39, 0.0), {0}), Error);
  EXPECT_THROW(pchip.refitAround(knots, {39}), Error);
  EXPECT_THROW(pchip.refitAround(decreasing, {5}), Error);
  EXPECT_EQ(pchip.knots(), knots);
}

TEST(Pchip, RejectsBadKnotsAndValues) {
  MatrixXd values(3, 1);
  values << 0.0, 1.0, 2.0;
  const auto message = [&](const std::vector<double>& knots, const MatrixXd& data) {
    try {
      Pchip pchip(knots, data);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({0.0, 1.0, 1.0}, values).find("knot 2"), std::string::npos);
  EXPECT_NE(message({0.0, 1.0, 1.0}, values).find("strictly increasing"), std::string::npos);
  EXPECT_NE(message({0.0, 2.0, 1.0}, values).find("strictly increasing"), std::string::npos);
  EXPECT_NE(message({0.0, NAN, 1.0}, values).find("knot 1 is not finite"), std::string::npos);
  EXPECT_NE(message({0.0, 1.0}, values).find("2 knots but 3 rows"), std::string::npos);
  EXPECT_NE(message({0.0}, values.topRows(1)).find("at least 2 knots"), std::string::npos);
  MatrixXd withNan = values;
  withNan(1, 0) = NAN;
  EXPECT_NE(message({0.0, 1.0, 2.0}, withNan).find("finite"), std::string::npos);
}

}  // namespace
}  // namespace arcplan::trajectory
