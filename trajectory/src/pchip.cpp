#include "arcplan/trajectory/pchip.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "arcplan/common/error.h"

namespace arcplan::trajectory {
namespace {

int sign(double value) { return (value > 0.0) - (value < 0.0); }

// Fritsch–Butland weighted harmonic mean of the secants around an interior knot; zero at a local
// extremum of the data (secants of opposite sign or one of them flat).
double interiorSlope(double hBefore, double hAfter, double secantBefore, double secantAfter) {
  if (secantBefore * secantAfter <= 0.0) return 0.0;
  const double weightBefore = 2.0 * hAfter + hBefore;
  const double weightAfter = hAfter + 2.0 * hBefore;
  return (weightBefore + weightAfter) / (weightBefore / secantBefore + weightAfter / secantAfter);
}

// Non-centred three-point slope at an end knot, limited so the end interval stays monotone.
double endSlope(double hNear, double hFar, double secantNear, double secantFar) {
  double slope = ((2.0 * hNear + hFar) * secantNear - hNear * secantFar) / (hNear + hFar);
  if (sign(slope) != sign(secantNear)) {
    slope = 0.0;
  } else if (sign(secantNear) != sign(secantFar) && std::abs(slope) > 3.0 * std::abs(secantNear)) {
    slope = 3.0 * secantNear;
  }
  return slope;
}

// Throws naming the first knot that is not finite or not above the one before it.
void checkKnots(const std::vector<double>& knots) {
  for (std::size_t k = 0; k < knots.size(); ++k) {
    if (!std::isfinite(knots[k])) throw Error("PCHIP: knot " + std::to_string(k) + " is not finite");
    if (k > 0 && !(knots[k] > knots[k - 1])) {
      throw Error("PCHIP: knots must be strictly increasing, but knot " + std::to_string(k) + " (" +
                  std::to_string(knots[k]) + ") is not greater than knot " + std::to_string(k - 1) + " (" +
                  std::to_string(knots[k - 1]) + ")");
    }
  }
}

}  // namespace

Pchip::Pchip(const std::vector<double>& knots, const Eigen::MatrixXd& values, PchipEnds ends) {
  fit(knots, values, ends);
}

void Pchip::fit(const std::vector<double>& knots, const Eigen::MatrixXd& values, PchipEnds ends) {
  const std::size_t n = knots.size();
  if (n < 2) throw Error("PCHIP: needs at least 2 knots, got " + std::to_string(n));
  if (static_cast<std::size_t>(values.rows()) != n) {
    throw Error("PCHIP: " + std::to_string(n) + " knots but " + std::to_string(values.rows()) + " rows of values");
  }
  checkKnots(knots);
  if (!values.allFinite()) throw Error("PCHIP: the values must be finite numbers");

  knots_ = knots;
  values_ = values;
  slopes_.resize(values.rows(), values.cols());
  for (Eigen::Index c = 0; c < values.cols(); ++c) {
    slopes_(0, c) = slopeAt(0, c, ends);
    slopes_(n - 1, c) = slopeAt(n - 1, c, ends);
    // Interior knots streamed (each secant computed once); the same expressions as slopeAt's, so the same bits.
    if (n == 2) continue;
    double hBefore = knots[1] - knots[0];
    double secantBefore = (values(1, c) - values(0, c)) / hBefore;
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const double hAfter = knots[k + 1] - knots[k];
      const double secantAfter = (values(k + 1, c) - values(k, c)) / hAfter;
      slopes_(k, c) = interiorSlope(hBefore, hAfter, secantBefore, secantAfter);
      hBefore = hAfter;
      secantBefore = secantAfter;
    }
  }
}

void Pchip::refitAround(const std::vector<double>& knots, const std::vector<std::size_t>& intervals, PchipEnds ends) {
  if (knots.size() != knots_.size()) {
    throw Error("PCHIP: a refit around intervals keeps the " + std::to_string(knots_.size()) + " knots, got " +
                std::to_string(knots.size()));
  }
  // Everything checked before anything changes: a refused refit leaves the fit as it was.
  checkKnots(knots);
  for (const std::size_t k : intervals) {
    if (k + 1 >= knots.size()) throw Error("PCHIP: no interval " + std::to_string(k) + " to refit");
  }
  knots_ = knots;
  for (const std::size_t k : intervals) {
    for (Eigen::Index c = 0; c < values_.cols(); ++c) {
      slopes_(k, c) = slopeAt(k, c, ends);
      slopes_(k + 1, c) = slopeAt(k + 1, c, ends);
    }
  }
}

double Pchip::slopeAt(std::size_t k, Eigen::Index c, PchipEnds ends) const {
  const std::size_t n = knots_.size();
  const auto h = [&](std::size_t i) { return knots_[i + 1] - knots_[i]; };
  const auto secant = [&](std::size_t i) { return (values_(i + 1, c) - values_(i, c)) / h(i); };
  if ((k == 0 || k == n - 1) && ends == PchipEnds::ZeroSlope) return 0.0;
  if (n == 2) return secant(0);
  if (k == 0) return endSlope(h(0), h(1), secant(0), secant(1));
  if (k == n - 1) return endSlope(h(n - 2), h(n - 3), secant(n - 2), secant(n - 3));
  return interiorSlope(h(k - 1), h(k), secant(k - 1), secant(k));
}

std::size_t Pchip::intervalOf(double t) const {
  const auto upper = std::upper_bound(knots_.begin(), knots_.end(), t);
  const auto index = static_cast<std::size_t>(std::max<std::ptrdiff_t>(upper - knots_.begin() - 1, 0));
  return std::min(index, knots_.size() - 2);
}

void Pchip::evaluate(double t, Eigen::Ref<Eigen::VectorXd> value) const {
  const std::size_t k = intervalOf(t);
  const double h = knots_[k + 1] - knots_[k];
  const double u = (t - knots_[k]) / h;
  const double u2 = u * u, u3 = u2 * u;
  value = (2 * u3 - 3 * u2 + 1) * values_.row(k).transpose() + ((u3 - 2 * u2 + u) * h) * slopes_.row(k).transpose() +
          (-2 * u3 + 3 * u2) * values_.row(k + 1).transpose() + ((u3 - u2) * h) * slopes_.row(k + 1).transpose();
}

void Pchip::evaluate(double t, Eigen::Ref<Eigen::VectorXd> value, Eigen::Ref<Eigen::VectorXd> firstDerivative,
                     Eigen::Ref<Eigen::VectorXd> secondDerivative) const {
  evaluateInInterval(intervalOf(t), t, value, firstDerivative, secondDerivative);
}

void Pchip::evaluateInInterval(std::size_t k, double t, Eigen::Ref<Eigen::VectorXd> value,
                               Eigen::Ref<Eigen::VectorXd> firstDerivative,
                               Eigen::Ref<Eigen::VectorXd> secondDerivative) const {
  const double h = knots_[k + 1] - knots_[k];
  const double u = (t - knots_[k]) / h;
  const double u2 = u * u, u3 = u2 * u;
  for (Eigen::Index c = 0; c < values_.cols(); ++c) {
    const double y0 = values_(k, c), y1 = values_(k + 1, c);
    const double m0 = slopes_(k, c) * h, m1 = slopes_(k + 1, c) * h;
    value[c] = (2 * u3 - 3 * u2 + 1) * y0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * y1 + (u3 - u2) * m1;
    firstDerivative[c] =
        ((6 * u2 - 6 * u) * y0 + (3 * u2 - 4 * u + 1) * m0 + (6 * u - 6 * u2) * y1 + (3 * u2 - 2 * u) * m1) / h;
    secondDerivative[c] = ((12 * u - 6) * y0 + (6 * u - 4) * m0 + (6 - 12 * u) * y1 + (6 * u - 2) * m1) / (h * h);
  }
}

}  // namespace arcplan::trajectory
