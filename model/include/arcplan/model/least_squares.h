#pragma once
// Linear least squares from the normal equations, robust to collinear regressors: columns are
// scaled to unit diagonal, and a column that the columns before it already explain (its share of
// variance not explained by them below 1e-10) is dropped and reported as not identifiable. The
// order of the columns therefore decides which of two collinear effects keeps the parameter.
//
// Working from Gram matrices lets cross-validation fit every fold by subtracting the fold's Gram
// from the total, without touching the samples again.
#include <vector>

#include <Eigen/Core>

namespace arcplan::model {

// Sufficient statistics of a regression: XᵀX, Xᵀy, yᵀy and the sample count.
struct NormalEquations {
  Eigen::MatrixXd gram;
  Eigen::VectorXd moment;
  double squares = 0.0;
  Eigen::Index samples = 0;

  static NormalEquations of(const Eigen::MatrixXd& columns, const Eigen::VectorXd& target);
  NormalEquations operator-(const NormalEquations& other) const;
  NormalEquations operator+(const NormalEquations& other) const;
  // The same statistics restricted to some columns (in the given order).
  NormalEquations select(const std::vector<int>& columns) const;
  // Sum of squared residuals of `coefficients` on these samples.
  double residualSquares(const Eigen::VectorXd& coefficients) const;
};

struct LinearSolution {
  Eigen::VectorXd coefficients;    // 0 where not identifiable
  Eigen::VectorXd standardErrors;  // NaN where not identifiable
  std::vector<bool> identifiable;
  int rank = 0;
  double residualSquares = 0.0;
};

// Solves min |Xθ - y|². Standard errors assume independent residuals of equal variance
// (σ² = RSS / (n - rank)); autocorrelated residuals make them optimistic.
LinearSolution solveLeastSquares(const NormalEquations& equations);

// Orthonormal columns spanning the columns of `design` (rank-revealing QR; none for an empty design).
Eigen::MatrixXd orthonormalBasis(const Eigen::MatrixXd& design);

}  // namespace arcplan::model
