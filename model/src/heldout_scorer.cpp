// Held-out scoring shared by the diagnosis of catalogue effects and the discovery of new terms, and
// the check of what the diagnosis proposes by the step itself.
#include <algorithm>
#include <cmath>

#include "arcplan/model/fitting.h"
#include "arcplan/model/least_squares.h"
#include "model_internal.h"

namespace arcplan::model::detail {

HeldOutScorer::HeldOutScorer(const Dataset& data, const Dataset* validation, Eigen::VectorXd targetTrain,
                             Eigen::VectorXd targetValidation, Eigen::MatrixXd baseTrain,
                             Eigen::MatrixXd baseValidation, int folds)
    : validation_(validation != nullptr),
      targetTrain_(std::move(targetTrain)),
      targetValidation_(std::move(targetValidation)),
      baseTrain_(std::move(baseTrain)),
      baseValidation_(std::move(baseValidation)) {
  if (validation_) return;
  // Contiguous blocks keep neighbouring (correlated) samples of a log in one fold; data without
  // time is interleaved.
  const Eigen::Index n = targetTrain_.size();
  members_.resize(static_cast<std::size_t>(folds));
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto fold =
        data.timeOrdered() ? static_cast<std::size_t>(i * folds / n) : static_cast<std::size_t>(i % folds);
    members_[fold].push_back(i);
  }
}

Eigen::Index HeldOutScorer::heldOutSamples() const {
  return validation_ ? targetValidation_.size() : targetTrain_.size();
}

std::pair<double, int> HeldOutScorer::score(const Eigen::MatrixXd& extraTrain, const Eigen::MatrixXd& extraValidation,
                                            Eigen::VectorXd* heldOutResidual) const {
  Eigen::MatrixXd train(baseTrain_.rows(), baseTrain_.cols() + extraTrain.cols());
  train << baseTrain_, extraTrain;
  if (validation_) {
    const LinearSolution solution = solveLeastSquares(NormalEquations::of(train, targetTrain_));
    Eigen::MatrixXd held(baseValidation_.rows(), train.cols());
    held << baseValidation_, extraValidation;
    Eigen::VectorXd residual = targetValidation_;
    if (held.cols() > 0) residual -= held * solution.coefficients;
    const double squares = residual.squaredNorm();
    if (heldOutResidual) *heldOutResidual = std::move(residual);
    return {squares, solution.rank};
  }
  // Cross-validation from per-fold normal equations: each fold is fitted on the total minus itself.
  std::vector<NormalEquations> perFold;
  NormalEquations total;
  for (std::size_t f = 0; f < members_.size(); ++f) {
    const auto& rows = members_[f];
    Eigen::MatrixXd x(static_cast<Eigen::Index>(rows.size()), train.cols());
    Eigen::VectorXd y(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t r = 0; r < rows.size(); ++r) {
      x.row(static_cast<Eigen::Index>(r)) = train.row(rows[r]);
      y[static_cast<Eigen::Index>(r)] = targetTrain_[rows[r]];
    }
    perFold.push_back(NormalEquations::of(x, y));
    total = f == 0 ? perFold.back() : total + perFold.back();
  }
  double squares = 0.0;
  int rank = 0;
  if (heldOutResidual) heldOutResidual->resize(targetTrain_.size());
  for (std::size_t f = 0; f < members_.size(); ++f) {
    const LinearSolution solution = solveLeastSquares(total - perFold[f]);
    squares += perFold[f].residualSquares(solution.coefficients);
    rank = std::max(rank, solution.rank);
    if (heldOutResidual) {
      for (auto i : members_[f]) {
        (*heldOutResidual)[i] = targetTrain_[i] - (train.cols() > 0 ? train.row(i).dot(solution.coefficients) : 0.0);
      }
    }
  }
  return {squares, rank};
}

double informationCriterion(double squaresWith, double squaresWithout, int addedParameters, double samples) {
  const double ratio = std::max(squaresWith, 1e-300) / std::max(squaresWithout, 1e-300);
  return samples * std::log(ratio) + addedParameters * std::log(samples);
}

double HeldOutBaseline::total() const {
  double sum = 0.0;
  for (double s : squares) sum += s;
  return sum;
}

void judgeCandidate(EffectCandidate& candidate, const std::vector<double>& squares, const std::vector<int>& ranks,
                    bool searched, const HeldOutBaseline& baseline, double minimumReduction) {
  const auto channels = squares.size();
  candidate.channelReduction.assign(channels, 0.0);
  candidate.joints.clear();
  candidate.score = 0.0;
  for (std::size_t c = 0; c < channels; ++c) {
    const int added = ranks[c] - baseline.rank[c] + (searched && ranks[c] > baseline.rank[c] ? 1 : 0);
    const auto n = static_cast<double>(baseline.scorers[c].heldOutSamples());
    const double criterion = informationCriterion(squares[c], baseline.squares[c], added, n);
    candidate.channelReduction[c] = 1.0 - std::sqrt(std::max(squares[c], 0.0) / std::max(baseline.squares[c], 1e-300));
    if (added > 0 && criterion < 0.0 && candidate.channelReduction[c] >= minimumReduction) {
      candidate.joints.push_back(static_cast<int>(c));
      candidate.score += criterion;
    }
  }
  candidate.suggested = !candidate.joints.empty();
  candidate.entry.joints = candidate.joints;
  // Suggested: the effect on its significant channels only; otherwise what it would do everywhere.
  double with = 0.0;
  for (std::size_t c = 0; c < channels; ++c) {
    const bool used = !candidate.suggested || std::find(candidate.joints.begin(), candidate.joints.end(),
                                                        static_cast<int>(c)) != candidate.joints.end();
    with += used ? squares[c] : baseline.squares[c];
  }
  const double total = baseline.total();
  candidate.heldoutReduction = total > 0.0 ? 1.0 - std::sqrt(with / total) : 0.0;
}

double noiseFloor(const Eigen::VectorXd& residual) {
  const Eigen::Index n = residual.size();
  if (n < 3) return 0.0;
  const Eigen::ArrayXd second =
      residual.segment(2, n - 2).array() - 2.0 * residual.segment(1, n - 2).array() + residual.head(n - 2).array();
  return std::sqrt(second.square().mean() / 6.0);
}

// The diagnosis' promise, checked by the step itself: a suggestion is proposed on a channel only if
// the step that `fit --add` runs (extendModel, or fitAdditions with kept parameters) lowers that
// channel's held-out error. The held-out scorer already predicts this for per-channel effects
// (the same columns, the same least squares); the check holds it for everything else too (a
// payload fitted jointly across channels, a column dropped as collinear) and reports the step's
// own numbers.
namespace {

std::vector<double> heldOutSquares(const FittedModel& model, const Dataset& validation) {
  std::vector<double> squares;
  const auto predictions = predictAll(model, validation);
  for (int c = 0; c < validation.channelCount(); ++c) {
    squares.push_back((validation.measured(c) - predictions[c]).squaredNorm());
  }
  return squares;
}

}  // namespace

void checkProposal(EffectCandidate& candidate, const FittedModel& base, bool keepParameters, const Dataset& data,
                   const Dataset& validation, double minimumReduction) {
  if (!candidate.suggested) return;
  // One set of arm parameters (a payload) is seen through the drive gains: without them there is no
  // step to run (fit --add says so), so nothing to propose.
  if (createEffect(candidate.entry)->sharedAcrossChannels() && !base.spec.hasEffect("drive_gain")) {
    candidate.suggested = false;
    return;
  }
  const std::vector<double> before = heldOutSquares(base, validation);
  // A shared effect refitted on fewer channels changes on the rest: check again until none is dropped
  // (every round keeps a subset, so this ends), so the joints proposed are the ones last scored.
  while (!candidate.joints.empty()) {
    EffectSpec entry = candidate.entry;
    entry.joints = candidate.joints;
    const FittedModel after = keepParameters ? fitAdditions(base, {entry}, data) : extendModel(base, {entry}, data);
    const std::vector<double> squares = heldOutSquares(after, validation);
    std::vector<int> kept;
    double with = 0.0, total = 0.0;
    for (int c = 0; c < validation.channelCount(); ++c) {
      const bool applied = std::find(candidate.joints.begin(), candidate.joints.end(), c) != candidate.joints.end();
      const double reduction = 1.0 - std::sqrt(squares[c] / std::max(before[c], 1e-300));
      if (applied) candidate.channelReduction[c] = reduction;
      if (applied && reduction >= minimumReduction) kept.push_back(c);
      with += squares[c];
      total += before[c];
    }
    candidate.heldoutReduction = total > 0.0 ? 1.0 - std::sqrt(with / total) : 0.0;
    if (kept.size() == candidate.joints.size()) break;
    candidate.joints = kept;
  }
  candidate.entry.joints = candidate.joints;
  candidate.suggested = !candidate.joints.empty() && candidate.heldoutReduction > 0.0;
}

}  // namespace arcplan::model::detail
