#include "arcplan/model/diagnose.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "arcplan/common/error.h"
#include "arcplan/model/fitting.h"
#include "arcplan/model/least_squares.h"

namespace arcplan::model {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string percent(double fraction) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.1f%%", 100.0 * fraction);
  return buffer;
}

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4g", value);
  return buffer;
}

double spread(const Eigen::VectorXd& values) {
  const double s = std::sqrt((values.array() - values.mean()).square().mean());
  return s > 1e-12 ? s : 1.0;
}

// Held-out sums of squares of one channel, for the base design alone and with extra columns.
class HeldOutScorer {
public:
  HeldOutScorer(const Dataset& data, const Dataset* validation, int channel, const Eigen::MatrixXd& baseTrain,
                const Eigen::MatrixXd* baseValidation, int folds)
      : validation_(validation), baseColumns_(baseTrain.cols()) {
    targetTrain_ = data.measured(channel) - data.basePrediction(channel);
    baseTrain_ = baseTrain;
    if (validation) {
      targetValidation_ = validation->measured(channel) - validation->basePrediction(channel);
      baseValidation_ = *baseValidation;
    } else {
      const Eigen::Index n = targetTrain_.size();
      fold_.resize(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        fold_[i] = data.timeOrdered() ? static_cast<int>(i * folds / n) : static_cast<int>(i % folds);
      }
      folds_ = folds;
    }
  }

  Eigen::Index heldOutSamples() const { return validation_ ? targetValidation_.size() : targetTrain_.size(); }

  // Held-out RSS and the rank of the fit with `extraTrain` / `extraValidation` appended.
  std::pair<double, int> score(const Eigen::MatrixXd& extraTrain, const Eigen::MatrixXd* extraValidation,
                               Eigen::VectorXd* heldOutResidual = nullptr) const {
    Eigen::MatrixXd train(baseTrain_.rows(), baseColumns_ + extraTrain.cols());
    train << baseTrain_, extraTrain;
    if (validation_) {
      const LinearSolution solution = solveLeastSquares(NormalEquations::of(train, targetTrain_));
      Eigen::MatrixXd held(baseValidation_.rows(), train.cols());
      held << baseValidation_, *extraValidation;
      const Eigen::VectorXd residual = targetValidation_ - held * solution.coefficients;
      if (heldOutResidual) *heldOutResidual = residual;
      return {residual.squaredNorm(), solution.rank};
    }
    // Cross-validation from per-fold normal equations.
    std::vector<NormalEquations> perFold;
    std::vector<std::vector<Eigen::Index>> members(static_cast<std::size_t>(folds_));
    for (Eigen::Index i = 0; i < fold_.size(); ++i) members[fold_[i]].push_back(i);
    NormalEquations total;
    for (int f = 0; f < folds_; ++f) {
      const auto& rows = members[f];
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
    for (int f = 0; f < folds_; ++f) {
      const LinearSolution solution = solveLeastSquares(total - perFold[f]);
      squares += perFold[f].residualSquares(solution.coefficients);
      rank = std::max(rank, solution.rank);
      if (heldOutResidual) {
        for (auto i : members[f]) (*heldOutResidual)[i] = targetTrain_[i] - train.row(i).dot(solution.coefficients);
      }
    }
    return {squares, rank};
  }

private:
  const Dataset* validation_;
  Eigen::Index baseColumns_;
  Eigen::VectorXd targetTrain_, targetValidation_;
  Eigen::MatrixXd baseTrain_, baseValidation_;
  Eigen::VectorXi fold_;
  int folds_ = 0;
};

std::string explain(const Effect& effect, const EffectCandidate& candidate, const Dataset& data) {
  std::string text = "The residual on " + describeChannels(data, candidate.joints) + " " + effect.residualPattern() +
                     ": " + effect.meaning() + ". Adding " + candidate.effect + " removes " +
                     percent(candidate.heldoutReduction) + " of the held-out residual (";
  for (std::size_t k = 0; k < candidate.joints.size(); ++k) {
    const int c = candidate.joints[k];
    text += (k ? ", " : "") + data.channelName(c) + " -" + percent(candidate.channelReduction[c]);
  }
  text += ")";
  if (!candidate.nonlinearName.empty()) {
    text += "; " + candidate.nonlinearName + " =";
    for (std::size_t k = 0; k < candidate.joints.size(); ++k) {
      text += (k ? ", " : " ") + number(candidate.nonlinear[candidate.joints[k]]);
    }
    text += " " + candidate.nonlinearUnit;
  }
  return text + ".";
}

ErrorSummary summaryFromSquares(const Dataset& heldData, const std::vector<double>& squares) {
  ErrorSummary summary;
  double total = 0.0;
  for (int c = 0; c < heldData.channelCount(); ++c) {
    const auto& measured = heldData.measured(c);
    ChannelError error;
    error.channel = heldData.channelName(c);
    error.samples = measured.size();
    error.rmse = std::sqrt(squares[c] / static_cast<double>(measured.size()));
    error.nrmse = error.rmse / spread(measured);
    const double variance = (measured.array() - measured.mean()).square().sum();
    error.r2 = variance > 0.0 ? 1.0 - squares[c] / variance : 0.0;
    total += error.nrmse * error.nrmse;
    summary.channels.push_back(error);
  }
  summary.overallNrmse = std::sqrt(total / std::max(1, heldData.channelCount()));
  return summary;
}

}  // namespace

std::string describeChannels(const Dataset& data, const std::vector<int>& channels) {
  if (channels.empty()) return "no channel";
  if (data.kind() == ModelKind::GearboxFtd) {
    std::string text;
    for (std::size_t k = 0; k < channels.size(); ++k) {
      text += (k == 0 ? "" : (k + 1 == channels.size() ? " and " : ", ")) + data.channelName(channels[k]);
    }
    return text;
  }
  std::vector<std::string> parts;
  for (std::size_t k = 0; k < channels.size();) {
    std::size_t end = k;
    while (end + 1 < channels.size() && channels[end + 1] == channels[end] + 1) ++end;
    if (end >= k + 1) {
      parts.push_back(std::to_string(channels[k]) + "–" + std::to_string(channels[end]));
    } else {
      parts.push_back(std::to_string(channels[k]));
    }
    k = end + 1;
  }
  const bool plural = channels.size() > 1;
  std::string text = plural ? "joints " : "joint ";
  for (std::size_t k = 0; k < parts.size(); ++k) {
    text += (k == 0 ? "" : (k + 1 == parts.size() ? " and " : ", ")) + parts[k];
  }
  return text;
}

Diagnosis diagnose(const ModelSpec& spec, const Dataset& data, const Dataset* validation, const DiagnoseOptions& options) {
  if (validation && validation->channelCount() != data.channelCount()) {
    throw Error(validation->source() + ": mismatched joint count: " + std::to_string(validation->channelCount()) +
                " channels, the data has " + std::to_string(data.channelCount()));
  }
  const FittedModel base = fitModel(spec, data);
  const int channels = data.channelCount();
  const int folds = std::max(2, options.folds);
  Diagnosis diagnosis;
  diagnosis.heldout = validation ? "validation data (" + validation->source() + ")"
                                 : std::to_string(folds) + "-fold " +
                                       (data.timeOrdered() ? "time-blocked" : "interleaved") + " cross-validation";
  const Dataset& heldData = validation ? *validation : data;

  // Per channel: base designs, the training residual, and the held-out base error.
  std::vector<HeldOutScorer> scorers;
  std::vector<Eigen::VectorXd> trainResidual(static_cast<std::size_t>(channels));
  std::vector<double> baseSquares(static_cast<std::size_t>(channels));
  std::vector<int> baseRank(static_cast<std::size_t>(channels));
  std::vector<Eigen::VectorXd> heldResidual(static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c) {
    const Eigen::MatrixXd train = designMatrix(base.effects, data, c);
    Eigen::MatrixXd held;
    if (validation) held = designMatrix(base.effects, *validation, c);
    scorers.emplace_back(data, validation, c, train, validation ? &held : nullptr, folds);
    trainResidual[c] = data.measured(c) - predict(base, data, c);
    const Eigen::MatrixXd noTrain(train.rows(), 0), noHeld(held.rows(), 0);
    const auto [squares, rank] = scorers.back().score(noTrain, validation ? &noHeld : nullptr, &heldResidual[c]);
    baseSquares[c] = squares;
    baseRank[c] = rank;
  }
  diagnosis.heldoutBase = summaryFromSquares(heldData, baseSquares);
  double baseTotal = 0.0;
  for (int c = 0; c < channels; ++c) baseTotal += baseSquares[c];

  std::vector<std::string> ids = options.candidates.empty() ? registeredEffects() : options.candidates;
  for (const auto& id : ids) {
    if (spec.hasEffect(id)) continue;
    EffectSpec effectSpec;
    effectSpec.id = id;
    const auto effect = createEffect(effectSpec);
    if (!effect->appliesTo(data.kind())) continue;
    std::string missing;
    for (const auto& signal : effect->requiredSignals()) {
      if (!data.hasSignal(signal) || (validation && !validation->hasSignal(signal))) missing = signal;
    }
    if (!missing.empty()) {
      diagnosis.skipped.push_back(id + ": needs signal '" + missing + "', which the data does not provide");
      continue;
    }
    EffectCandidate candidate;
    candidate.effect = id;
    candidate.channelReduction.assign(static_cast<std::size_t>(channels), 0.0);
    candidate.nonlinear.assign(static_cast<std::size_t>(channels), kNaN);
    const auto nonlinear = effect->nonlinearParameter();
    if (nonlinear) {
      candidate.nonlinearName = nonlinear->name;
      candidate.nonlinearUnit = nonlinear->unit;
    }
    const auto parameters = static_cast<Eigen::Index>(effect->parameterNames().size());
    std::vector<double> candidateSquares(static_cast<std::size_t>(channels));
    for (int c = 0; c < channels; ++c) {
      const double value = nonlinear ? effect->searchNonlinear(data, c, trainResidual[c]) : 0.0;
      candidate.nonlinear[c] = nonlinear ? value : kNaN;
      Eigen::MatrixXd extraTrain(data.samples(c), parameters), extraHeld;
      effect->regressor(data, c, value, extraTrain);
      if (validation) {
        extraHeld.resize(validation->samples(c), parameters);
        effect->regressor(*validation, c, value, extraHeld);
      }
      const auto [squares, rank] = scorers[c].score(extraTrain, validation ? &extraHeld : nullptr);
      candidateSquares[c] = squares;
      const int added = rank - baseRank[c] + (nonlinear && rank > baseRank[c] ? 1 : 0);
      const auto n = static_cast<double>(scorers[c].heldOutSamples());
      const double ratio = std::max(squares, 1e-300) / std::max(baseSquares[c], 1e-300);
      const double criterion = n * std::log(ratio) + added * std::log(n);
      candidate.channelReduction[c] = 1.0 - std::sqrt(ratio);
      if (added > 0 && criterion < 0.0 && candidate.channelReduction[c] >= options.minimumReduction) {
        candidate.joints.push_back(c);
        candidate.score += criterion;
      }
    }
    candidate.suggested = !candidate.joints.empty();
    // Suggested: the effect on its significant channels only; otherwise what it would do everywhere.
    double withEffect = 0.0;
    for (int c = 0; c < channels; ++c) {
      const bool used = !candidate.suggested ||
                        std::find(candidate.joints.begin(), candidate.joints.end(), c) != candidate.joints.end();
      withEffect += used ? candidateSquares[c] : baseSquares[c];
    }
    candidate.heldoutReduction = baseTotal > 0.0 ? 1.0 - std::sqrt(withEffect / baseTotal) : 0.0;
    if (candidate.suggested) candidate.explanation = explain(*effect, candidate, data);
    diagnosis.ranking.push_back(std::move(candidate));
  }
  // Reductions equal to 0.1 percentage point are a tie; the information criterion (fewer
  // parameters for the same gain) decides it.
  std::stable_sort(diagnosis.ranking.begin(), diagnosis.ranking.end(), [](const auto& a, const auto& b) {
    if (a.suggested != b.suggested) return a.suggested;
    const double reductionA = std::floor(1000.0 * a.heldoutReduction), reductionB = std::floor(1000.0 * b.heldoutReduction);
    if (reductionA != reductionB) return reductionA > reductionB;
    return a.score < b.score;
  });

  diagnosis.residualFollows = residualCorrelations(heldData, heldResidual);
  if (!diagnosis.ranking.empty() && diagnosis.ranking.front().suggested) {
    diagnosis.summary = diagnosis.ranking.front().explanation;
    for (std::size_t k = 1; k < diagnosis.ranking.size() && k < 3 && diagnosis.ranking[k].suggested; ++k) {
      diagnosis.summary += "\nNext: " + diagnosis.ranking[k].explanation;
    }
  } else {
    diagnosis.summary = "No effect lowers the held-out error significantly (each must remove at least " +
                        percent(options.minimumReduction) + " of a channel's held-out residual and pass the "
                        "information criterion)";
    if (!diagnosis.ranking.empty()) {
      diagnosis.summary += "; the closest, " + diagnosis.ranking.front().effect + ", would change it by " +
                           percent(-diagnosis.ranking.front().heldoutReduction);
    }
    diagnosis.summary += ".";
    if (diagnosis.residualFollows.empty()) {
      diagnosis.summary += " The held-out residual correlates with none of the signals (|r| < 0.1): it looks like noise.";
    } else {
      diagnosis.summary += " The held-out residual still follows:";
      for (std::size_t k = 0; k < diagnosis.residualFollows.size() && k < 5; ++k) {
        const auto& follow = diagnosis.residualFollows[k];
        diagnosis.summary += (k ? ", " : " ") + follow.signal + " on " + follow.channel + " (r = " + number(follow.correlation) + ")";
      }
      diagnosis.summary += ".";
    }
  }
  return diagnosis;
}

}  // namespace arcplan::model
