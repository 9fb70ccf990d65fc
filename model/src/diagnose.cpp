#include "arcplan/model/diagnose.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/model/fitting.h"
#include "arcplan/model/least_squares.h"
#include "arcplan/model/term_library.h"
#include "model_internal.h"

namespace arcplan::model {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A discovered term must leave at most this share of a catalogue effect's held-out residual RMS
// to be ranked above it (see diagnose.h).
constexpr double kDiscoveryMargin = 0.99;

double spread(const Eigen::VectorXd& values) {
  const double s = std::sqrt((values.array() - values.mean()).square().mean());
  return s > 1e-12 ? s : 1.0;
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

// The model as it is on every channel: its columns (or, kept fixed, its prediction) and the
// held-out error.
detail::HeldOutBaseline makeBaseline(const FittedModel& model, bool kept, const Dataset& data,
                                     const Dataset* validation, int folds) {
  detail::HeldOutBaseline baseline;
  for (int c = 0; c < data.channelCount(); ++c) {
    Eigen::MatrixXd train, held;
    Eigen::VectorXd targetTrain = data.measured(c) - data.basePrediction(c), targetHeld;
    if (validation) targetHeld = validation->measured(c) - validation->basePrediction(c);
    if (kept) {
      targetTrain = data.measured(c) - predict(model, data, c);
      train.resize(data.samples(c), 0);
      if (validation) {
        targetHeld = validation->measured(c) - predict(model, *validation, c);
        held.resize(validation->samples(c), 0);
      }
    } else {
      train = designMatrix(model.effects, data, c);
      if (validation) held = designMatrix(model.effects, *validation, c);
    }
    baseline.trainBasis.push_back(orthonormalBasis(train));
    baseline.trainResidual.push_back(data.measured(c) - predict(model, data, c));
    baseline.scorers.emplace_back(data, validation, std::move(targetTrain), std::move(targetHeld), std::move(train),
                                  std::move(held), folds);
    Eigen::VectorXd residual;
    const Eigen::MatrixXd none(data.samples(c), 0), noneHeld(validation ? validation->samples(c) : 0, 0);
    const auto [squares, rank] = baseline.scorers.back().score(none, noneHeld, &residual);
    baseline.squares.push_back(squares);
    baseline.rank.push_back(rank);
    baseline.heldOutResidual.push_back(std::move(residual));
  }
  return baseline;
}

// Columns of `effect` on one channel of a dataset.
Eigen::MatrixXd columnsOf(const Effect& effect, const Dataset& data, int channel, double nonlinear) {
  Eigen::MatrixXd columns(data.samples(channel), static_cast<Eigen::Index>(effect.parameterNames().size()));
  effect.regressor(data, channel, nonlinear, columns);
  return columns;
}

EffectCandidate scoreCatalogueEffect(const Effect& effect, const Dataset& data, const Dataset* validation,
                                     const detail::HeldOutBaseline& baseline, double minimumReduction) {
  const int channels = data.channelCount();
  EffectCandidate candidate;
  candidate.effect = effect.id();
  candidate.entry.id = effect.id();
  candidate.nonlinear.assign(static_cast<std::size_t>(channels), kNaN);
  const auto nonlinear = effect.nonlinearParameter();
  if (nonlinear) {
    candidate.nonlinearName = nonlinear->name;
    candidate.nonlinearUnit = nonlinear->unit;
  }
  std::vector<double> squares(static_cast<std::size_t>(channels));
  std::vector<int> ranks(static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c) {
    const double value =
        nonlinear ? effect.searchNonlinear(data, c, baseline.trainResidual[c], baseline.trainBasis[c]) : 0.0;
    if (nonlinear) candidate.nonlinear[c] = value;
    const Eigen::MatrixXd train = columnsOf(effect, data, c, value);
    const Eigen::MatrixXd held = validation ? columnsOf(effect, *validation, c, value) : Eigen::MatrixXd();
    std::tie(squares[c], ranks[c]) = baseline.scorers[c].score(train, held);
  }
  detail::judgeCandidate(candidate, squares, ranks, nonlinear.has_value(), baseline, minimumReduction);
  return candidate;
}

// The suggested catalogue effects together: the share of the held-out residual they remove.
double catalogueTogether(const std::vector<EffectCandidate>& ranking, const Dataset& data, const Dataset* validation,
                         const detail::HeldOutBaseline& baseline) {
  double with = 0.0;
  for (int c = 0; c < data.channelCount(); ++c) {
    Eigen::MatrixXd train(data.samples(c), 0), held(validation ? validation->samples(c) : 0, 0);
    for (const auto& candidate : ranking) {
      if (candidate.discovered ||
          std::find(candidate.joints.begin(), candidate.joints.end(), c) == candidate.joints.end()) {
        continue;
      }
      const auto effect = createEffect(candidate.entry);
      const Eigen::MatrixXd extra = columnsOf(*effect, data, c, candidate.nonlinear[c]);
      train.conservativeResize(Eigen::NoChange, train.cols() + extra.cols());
      train.rightCols(extra.cols()) = extra;
      if (validation) {
        const Eigen::MatrixXd extraHeld = columnsOf(*effect, *validation, c, candidate.nonlinear[c]);
        held.conservativeResize(Eigen::NoChange, held.cols() + extraHeld.cols());
        held.rightCols(extraHeld.cols()) = extraHeld;
      }
    }
    with += train.cols() > 0 ? baseline.scorers[c].score(train, held).first : baseline.squares[c];
  }
  const double total = baseline.total();
  return total > 0.0 ? 1.0 - std::sqrt(with / total) : 0.0;
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

namespace {

FittedModel baseModel(const ModelSpec& spec, const Dataset& data, const DiagnoseOptions& options) {
  return options.keepParameters ? modelFromParameters(spec, data, false) : fitModel(spec, data);
}

// The diagnosis proper, on logs without events.
Diagnosis diagnoseWithoutEvents(const ModelSpec& spec, const Dataset& data, const Dataset* validation,
                                const DiagnoseOptions& options) {
  const FittedModel base = baseModel(spec, data, options);
  Diagnosis diagnosis;
  diagnosis.heldout = validation ? "validation data (" + validation->source() + ")"
                                 : std::to_string(options.folds) + "-fold " +
                                       (data.timeOrdered() ? "time-blocked" : "interleaved") + " cross-validation";
  if (options.keepParameters) diagnosis.heldout += ", parameters of " + spec.source.string() + " kept fixed";
  const Dataset& heldData = validation ? *validation : data;
  auto baseline = makeBaseline(base, options.keepParameters, data, validation, options.folds);
  if (validation) {
    baseline.checkStep = [&](EffectCandidate& candidate) {
      detail::checkProposal(candidate, base, options.keepParameters, data, *validation, options.minimumReduction);
    };
  }
  diagnosis.heldoutBase = summaryFromSquares(heldData, baseline.squares);

  const std::vector<std::string> ids = options.candidates.empty() ? registeredEffects() : options.candidates;
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
    auto candidate = scoreCatalogueEffect(*effect, data, validation, baseline, options.minimumReduction);
    if (baseline.checkStep) baseline.checkStep(candidate);
    // One physical payload for the arm: fitted jointly on the channels it helps, reported in kg.
    if (candidate.suggested && effect->sharedAcrossChannels() && spec.hasEffect("drive_gain")) {
      const FittedModel with = options.keepParameters ? fitAdditions(base, {candidate.entry}, data)
                                                      : extendModel(base, {candidate.entry}, data);
      const auto& fit = with.effects.back();
      candidate.quantities = fit.effect->physicalQuantities(fit.shared, fit.sharedCovariance);
    }
    if (candidate.suggested) candidate.explanation = detail::explainCandidate(*effect, candidate, data);
    diagnosis.ranking.push_back(std::move(candidate));
  }
  if (options.discover) {
    for (auto& candidate : detail::discoverTerms(data, validation, baseline, options)) {
      diagnosis.ranking.push_back(std::move(candidate));
    }
  }
  // Reductions equal to 0.1 percentage point are a tie; the information criterion (fewer
  // parameters for the same gain) decides it. Discovered terms count with their margin.
  auto key = [](const EffectCandidate& c) {
    const double reduction = c.discovered ? 1.0 - (1.0 - c.heldoutReduction) / kDiscoveryMargin : c.heldoutReduction;
    return std::floor(1000.0 * reduction);
  };
  std::stable_sort(diagnosis.ranking.begin(), diagnosis.ranking.end(), [&](const auto& a, const auto& b) {
    if (a.suggested != b.suggested) return a.suggested;
    if (key(a) != key(b)) return key(a) > key(b);
    return a.score < b.score;
  });

  if (data.timeOrdered()) {
    double noise = 0.0;
    for (int c = 0; c < heldData.channelCount(); ++c) {
      diagnosis.noiseFloor.push_back(detail::noiseFloor(baseline.heldOutResidual[c]));
      noise += std::pow(diagnosis.noiseFloor.back(), 2) * static_cast<double>(baseline.heldOutResidual[c].size());
    }
    const double total = baseline.total();
    diagnosis.explainable = total > 0.0 ? std::max(0.0, 1.0 - std::sqrt(noise / total)) : 0.0;
  } else {
    diagnosis.noiseFloor.assign(static_cast<std::size_t>(heldData.channelCount()), kNaN);
    diagnosis.explainable = kNaN;
  }
  diagnosis.catalogueExplains = catalogueTogether(diagnosis.ranking, data, validation, baseline);
  diagnosis.residualFollows = residualCorrelations(heldData, baseline.heldOutResidual);
  diagnosis.summary = detail::diagnosisSummary(diagnosis, options.minimumReduction);
  return diagnosis;
}

}  // namespace

void checkFolds(int folds, const std::string& name) {
  if (folds < 2) throw Error(name + " must be an integer >= 2 (cross-validation folds), got " + std::to_string(folds));
}

void checkMinimumReduction(double fraction, const std::string& name) {
  if (!(fraction >= 0.0 && fraction <= 1.0)) {
    throw Error(name + " must be a fraction from 0 to 1 (of a channel's held-out residual RMS), got " +
                formatNumber(fraction, 6));
  }
}

Diagnosis diagnose(const ModelSpec& spec, const Dataset& data, const Dataset* validation,
                   const DiagnoseOptions& options) {
  checkFolds(options.folds, "folds");
  checkMinimumReduction(options.minimumReduction, "minimumReduction");
  if (validation && validation->channelCount() != data.channelCount()) {
    throw Error(validation->source() + ": mismatched joint count: " + std::to_string(validation->channelCount()) +
                " channels, the data has " + std::to_string(data.channelCount()));
  }
  if (!options.leaveOutEvents || !data.timeOrdered()) return diagnoseWithoutEvents(spec, data, validation, options);
  const EventFreeData clean = leaveOutEvents(baseModel(spec, data, options), data, validation);
  const auto& dataEvents = clean.dataEvents;
  const auto& validationEvents = clean.validationEvents;
  if (dataEvents.empty() && validationEvents.empty()) return diagnoseWithoutEvents(spec, data, validation, options);
  Diagnosis diagnosis = diagnoseWithoutEvents(spec, clean.data(), clean.validation(), options);
  std::string leftOut;
  if (!dataEvents.empty()) leftOut += "data: " + describeEvents(dataEvents, data);
  if (!validationEvents.empty()) {
    leftOut +=
        (leftOut.empty() ? "" : "; ") + std::string("validation: ") + describeEvents(validationEvents, *validation);
  }
  diagnosis.heldout += ", event windows left out";
  diagnosis.summary =
      "Left out as moments, not effects (the residual leaves its noise band and comes back): " + leftOut + ".\n" +
      diagnosis.summary;
  diagnosis.dataEvents = dataEvents;
  diagnosis.validationEvents = validationEvents;
  return diagnosis;
}

}  // namespace arcplan::model
