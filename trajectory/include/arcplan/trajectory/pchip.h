#pragma once
// Monotone piecewise-cubic Hermite interpolation (PCHIP, Fritsch–Carlson), vector-valued: every
// component (column) is interpolated independently over the same strictly increasing knots.
//
// The slopes at the knots are the weighted harmonic means of the neighbouring secants (Fritsch &
// Butland), zero where the data has a local extremum, so each component is monotone wherever its
// data is and never leaves the range of the two knots around it (no overshoot, unlike a cubic
// spline): joint paths that respect their limits at the knots respect them in between. The
// interpolant is C¹; the second derivative jumps at the knots.
//
// Hand-written rather than taken from a library: the Debian stack has no PCHIP in C++ (Eigen's
// unsupported Splines are not shape-preserving), and the time scaling refits it many times per
// trajectory, so it reuses its storage.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace arcplan::trajectory {

// How the slopes at the first and last knot are chosen.
enum class PchipEnds {
  ShapePreserving,  // one-sided three-point estimate, limited to keep monotonicity (as MATLAB/SciPy)
  ZeroSlope,        // first derivative 0 at both ends (a motion that starts and ends at rest)
};

class Pchip {
public:
  Pchip() = default;
  // knots: strictly increasing, finite, at least 2. values: one row per knot, one column per
  // component. Throws arcplan::Error naming the offending knot index.
  Pchip(const std::vector<double>& knots, const Eigen::MatrixXd& values, PchipEnds ends = PchipEnds::ShapePreserving);

  // Refits in place (reusing the storage when the sizes do not change).
  void fit(const std::vector<double>& knots, const Eigen::MatrixXd& values,
           PchipEnds ends = PchipEnds::ShapePreserving);
  // After fit(), the same values over moved knots (as many), where only `intervals` will be evaluated: their
  // interpolants are then exactly fit()'s on these knots (a slope depends on its knot's neighbours alone), the
  // others stale until the next fit(). The time scaling re-times a few intervals at a time and refits a whole
  // trajectory's knots no more often than it samples all of them.
  void refitAround(const std::vector<double>& knots, const std::vector<std::size_t>& intervals,
                   PchipEnds ends = PchipEnds::ShapePreserving);

  std::size_t knotCount() const { return knots_.size(); }
  Eigen::Index dimension() const { return values_.cols(); }
  double endKnot() const { return knots_.back(); }
  const std::vector<double>& knots() const { return knots_; }
  // Slopes (first derivatives) at the knots, same layout as the values.
  const Eigen::MatrixXd& slopes() const { return slopes_; }

  // Index k of the interval [knot k, knot k+1] that contains t (clamped to the first/last one).
  std::size_t intervalOf(double t) const;

  // Value (and first and second derivative) at t; t outside the knots extrapolates the end cubics.
  // The outputs must have dimension() rows; fixed-size vectors (robot::Vector6) bind directly.
  void evaluate(double t, Eigen::Ref<Eigen::VectorXd> value) const;
  void evaluate(double t, Eigen::Ref<Eigen::VectorXd> value, Eigen::Ref<Eigen::VectorXd> firstDerivative,
                Eigen::Ref<Eigen::VectorXd> secondDerivative) const;
  // Same on a known interval (skips the search; for sequential sampling).
  void evaluateInInterval(std::size_t interval, double t, Eigen::Ref<Eigen::VectorXd> value,
                          Eigen::Ref<Eigen::VectorXd> firstDerivative,
                          Eigen::Ref<Eigen::VectorXd> secondDerivative) const;

private:
  // The slope at knot k of component c from the knots and values stored (the rule of the header's comment).
  double slopeAt(std::size_t k, Eigen::Index c, PchipEnds ends) const;

  std::vector<double> knots_;
  Eigen::MatrixXd values_;
  Eigen::MatrixXd slopes_;
};

}  // namespace arcplan::trajectory
