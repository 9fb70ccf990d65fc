#include "arcplan/model/least_squares.h"

#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/QR>

namespace arcplan::model {

NormalEquations NormalEquations::of(const Eigen::MatrixXd& columns, const Eigen::VectorXd& target) {
  NormalEquations e;
  e.gram = Eigen::MatrixXd::Zero(columns.cols(), columns.cols());
  // A model without parameters (joint_tracking's base) has no columns; Eigen's product kernel must
  // not see the empty matrix (UBSan flags its null data pointer).
  if (columns.cols() > 0 && columns.rows() > 0) {
    e.gram.selfadjointView<Eigen::Lower>().rankUpdate(columns.transpose());
  }
  e.gram.triangularView<Eigen::StrictlyUpper>() = e.gram.transpose();
  e.moment = columns.transpose() * target;
  e.squares = target.squaredNorm();
  e.samples = target.size();
  return e;
}

NormalEquations NormalEquations::operator-(const NormalEquations& other) const {
  return {gram - other.gram, moment - other.moment, squares - other.squares, samples - other.samples};
}

NormalEquations NormalEquations::operator+(const NormalEquations& other) const {
  return {gram + other.gram, moment + other.moment, squares + other.squares, samples + other.samples};
}

NormalEquations NormalEquations::select(const std::vector<int>& columns) const {
  NormalEquations e;
  const auto p = static_cast<Eigen::Index>(columns.size());
  e.gram.resize(p, p);
  e.moment.resize(p);
  for (Eigen::Index i = 0; i < p; ++i) {
    e.moment[i] = moment[columns[i]];
    for (Eigen::Index k = 0; k < p; ++k) e.gram(i, k) = gram(columns[i], columns[k]);
  }
  e.squares = squares;
  e.samples = samples;
  return e;
}

double NormalEquations::residualSquares(const Eigen::VectorXd& coefficients) const {
  if (coefficients.size() == 0) return squares;
  return std::max(0.0, squares - 2.0 * coefficients.dot(moment) + coefficients.dot(gram * coefficients));
}

LinearSolution solveLeastSquares(const NormalEquations& e) {
  const Eigen::Index p = e.gram.rows();
  LinearSolution solution;
  solution.coefficients = Eigen::VectorXd::Zero(p);
  solution.standardErrors = Eigen::VectorXd::Constant(p, std::numeric_limits<double>::quiet_NaN());
  solution.identifiable.assign(static_cast<std::size_t>(p), false);
  if (p == 0) {
    solution.residualSquares = e.squares;
    return solution;
  }
  // Scale to unit diagonal, then an incremental Cholesky that skips columns whose pivot (the part
  // of the column not explained by the kept ones) vanishes.
  Eigen::VectorXd scale(p);
  for (Eigen::Index i = 0; i < p; ++i) scale[i] = e.gram(i, i) > 0.0 ? 1.0 / std::sqrt(e.gram(i, i)) : 0.0;
  const Eigen::MatrixXd scaled = scale.asDiagonal() * e.gram * scale.asDiagonal();
  std::vector<int> kept;
  Eigen::MatrixXd factor = Eigen::MatrixXd::Zero(p, p);
  for (Eigen::Index i = 0; i < p; ++i) {
    if (scale[i] == 0.0) continue;
    Eigen::VectorXd row(static_cast<Eigen::Index>(kept.size()));
    for (std::size_t a = 0; a < kept.size(); ++a) {
      double value = scaled(i, kept[a]);
      for (std::size_t b = 0; b < a; ++b) value -= row[static_cast<Eigen::Index>(b)] * factor(kept[a], kept[b]);
      row[static_cast<Eigen::Index>(a)] = value / factor(kept[a], kept[a]);
    }
    const double pivot = scaled(i, i) - row.squaredNorm();
    if (pivot < 1e-10) continue;
    for (std::size_t a = 0; a < kept.size(); ++a) factor(i, kept[a]) = row[static_cast<Eigen::Index>(a)];
    factor(i, i) = std::sqrt(pivot);
    kept.push_back(static_cast<int>(i));
  }
  const auto rank = static_cast<Eigen::Index>(kept.size());
  solution.rank = static_cast<int>(rank);
  if (rank == 0) {
    solution.residualSquares = e.squares;
    return solution;
  }
  Eigen::MatrixXd gram(rank, rank);
  Eigen::VectorXd moment(rank);
  for (Eigen::Index a = 0; a < rank; ++a) {
    moment[a] = e.moment[kept[a]] * scale[kept[a]];
    for (Eigen::Index b = 0; b < rank; ++b) gram(a, b) = scaled(kept[a], kept[b]);
  }
  const Eigen::LLT<Eigen::MatrixXd> cholesky(gram);
  const Eigen::VectorXd scaledCoefficients = cholesky.solve(moment);
  for (Eigen::Index a = 0; a < rank; ++a) {
    solution.coefficients[kept[a]] = scaledCoefficients[a] * scale[kept[a]];
    solution.identifiable[static_cast<std::size_t>(kept[a])] = true;
  }
  solution.residualSquares = e.residualSquares(solution.coefficients);
  const double dof = static_cast<double>(e.samples - rank);
  if (dof > 0) {
    const double variance = solution.residualSquares / dof;
    const Eigen::MatrixXd inverse = cholesky.solve(Eigen::MatrixXd::Identity(rank, rank));
    for (Eigen::Index a = 0; a < rank; ++a) {
      solution.standardErrors[kept[a]] = std::sqrt(variance * inverse(a, a)) * scale[kept[a]];
    }
  }
  return solution;
}

Eigen::MatrixXd orthonormalBasis(const Eigen::MatrixXd& design) {
  if (design.cols() == 0 || design.rows() == 0) return Eigen::MatrixXd(design.rows(), 0);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
  return qr.householderQ() * Eigen::MatrixXd::Identity(design.rows(), qr.rank());
}

}  // namespace arcplan::model
