// Fitting (fitting.h): per-channel least squares, the joint fit of shared (payload) parameters,
// kept models and the loop's step share the effect bookkeeping here (a little over 400 lines).
#include "arcplan/model/fitting.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "arcplan/common/error.h"
#include "arcplan/model/least_squares.h"

namespace arcplan::model {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Eigen::Index columnCount(const std::vector<EffectFit>& effects, int channel) {
  Eigen::Index count = 0;
  for (const auto& fit : effects) {
    if (fit.applied[channel]) count += static_cast<Eigen::Index>(fit.effect->parameterNames().size());
  }
  return count;
}

// Writes a solution's coefficients into the applied effects with `include` (in design order).
void assignCoefficients(std::vector<EffectFit>& effects, int channel, const std::vector<bool>& include,
                        const Eigen::VectorXd& coefficients, const Eigen::VectorXd& errors) {
  Eigen::Index column = 0;
  for (std::size_t e = 0; e < effects.size(); ++e) {
    if (!include[e] || !effects[e].applied[channel]) continue;
    const auto count = static_cast<Eigen::Index>(effects[e].effect->parameterNames().size());
    effects[e].values[channel] = coefficients.segment(column, count);
    effects[e].standardErrors[channel] = errors.segment(column, count);
    column += count;
  }
}

std::vector<EffectFit> subset(const std::vector<EffectFit>& effects, const std::vector<bool>& include) {
  std::vector<EffectFit> chosen;
  for (std::size_t e = 0; e < effects.size(); ++e) {
    if (include[e]) chosen.push_back(effects[e]);
  }
  return chosen;
}

// Least squares of the applied effects with `include` on one channel, against `target`.
void solveChannel(std::vector<EffectFit>& effects, const Dataset& data, int channel, const std::vector<bool>& include,
                  const Eigen::VectorXd& target) {
  const Eigen::MatrixXd columns = designMatrix(subset(effects, include), data, channel);
  const LinearSolution solution = solveLeastSquares(NormalEquations::of(columns, target));
  assignCoefficients(effects, channel, include, solution.coefficients, solution.standardErrors);
}

Eigen::VectorXd contribution(const EffectFit& fit, const Dataset& data, int channel) {
  Eigen::MatrixXd columns(data.samples(channel), static_cast<Eigen::Index>(fit.effect->parameterNames().size()));
  fit.effect->regressor(data, channel, fit.nonlinear[channel], columns);
  return columns * fit.values[channel];
}

Eigen::VectorXd residualOf(const std::vector<EffectFit>& effects, const Dataset& data, int channel,
                           const std::vector<bool>& include, Eigen::VectorXd residual) {
  for (std::size_t e = 0; e < effects.size(); ++e) {
    if (include[e] && effects[e].applied[channel]) residual -= contribution(effects[e], data, channel);
  }
  return residual;
}

// Per channel: nonlinear parameters searched (those not yet known), then the linear ones of every
// effect in `free`.
void fitChannels(std::vector<EffectFit>& effects, const Dataset& data, const std::vector<bool>& free,
                 const std::vector<Eigen::VectorXd>& targets) {
  const std::size_t count = effects.size();
  for (int c = 0; c < data.channelCount(); ++c) {
    // Effects with known parameters first; each nonlinear effect then searches its parameter on
    // what the others leave, twice round so that two searched effects settle against each other.
    std::vector<bool> include(count);
    std::vector<std::size_t> nonlinear;
    for (std::size_t e = 0; e < count; ++e) {
      const bool searched = effects[e].effect->nonlinearParameter().has_value() && std::isnan(effects[e].nonlinear[c]);
      include[e] = free[e] && !searched;
      if (free[e] && searched && effects[e].applied[c]) nonlinear.push_back(e);
    }
    for (int round = 0; round < (nonlinear.size() > 1 ? 2 : 1); ++round) {
      for (std::size_t e : nonlinear) {
        include[e] = false;
        solveChannel(effects, data, c, include, targets[c]);
        const Eigen::VectorXd residual = residualOf(effects, data, c, include, targets[c]);
        const Eigen::MatrixXd basis = orthonormalBasis(designMatrix(subset(effects, include), data, c));
        effects[e].nonlinear[c] = effects[e].effect->searchNonlinear(data, c, residual, basis);
        include[e] = true;
      }
    }
    solveChannel(effects, data, c, free, targets[c]);
  }
}

// Channel c's drive gain (amps per N·m): the fitted drive_gain coefficient.
double driveGain(const std::vector<EffectFit>& effects, int gainEffect, int channel) {
  return gainEffect >= 0 && effects[gainEffect].applied[channel] ? effects[gainEffect].values[channel][0] : 0.0;
}

// The shared effect `e` and the per-channel effects in `free`, jointly (Gauss–Newton on the one
// bilinear term): channel c predicts k_c·(tau_c + Y_c·θ) + others_c when its drive gain k_c is
// free, k_c·Y_c·θ + others_c when it is kept. Linearised at θ0, every channel's parameters and θ
// come from one stacked least-squares solve, each channel weighted by 1/σ_c² (its residual
// variance), until θ settles. (Alternating between θ and the gains stalls: on the wrists the
// payload's torque is nearly proportional to the arm's own, so gain and mass trade off there.)
void fitShared(std::vector<EffectFit>& effects, std::size_t e, const Dataset& data, const std::vector<bool>& free,
               const std::vector<Eigen::VectorXd>& targets) {
  auto& shared = effects[e];
  int gainEffect = -1;
  for (std::size_t k = 0; k < effects.size(); ++k) {
    if (effects[k].effect->id() == "drive_gain") gainEffect = static_cast<int>(k);
  }
  if (gainEffect < 0) {
    throw Error("effect '" + shared.effect->id() +
                "': one set of physical parameters for the arm is seen in each "
                "joint's current through its drive gain; add drive_gain to the model");
  }
  const bool gainFree = free[static_cast<std::size_t>(gainEffect)];
  const auto parameters = static_cast<Eigen::Index>(shared.effect->parameterNames().size());
  const auto freeEffects = subset(effects, free);
  struct Channel {
    int index;
    Eigen::MatrixXd design, payload;
    Eigen::Index gainColumn = -1, offset = 0;
    double variance = 1.0;
  };
  std::vector<Channel> channels;
  Eigen::Index unknowns = 0;
  for (int c = 0; c < data.channelCount(); ++c) {
    if (!shared.applied[c]) continue;
    Channel channel{c, designMatrix(freeEffects, data, c), Eigen::MatrixXd(data.samples(c), parameters)};
    shared.effect->regressor(data, c, 0.0, channel.payload);
    Eigen::Index column = 0;
    for (std::size_t k = 0; k < effects.size(); ++k) {
      if (!free[k] || !effects[k].applied[c]) continue;
      if (static_cast<int>(k) == gainEffect) channel.gainColumn = column;
      column += static_cast<Eigen::Index>(effects[k].effect->parameterNames().size());
    }
    channel.offset = unknowns;
    unknowns += channel.design.cols();
    const Eigen::VectorXd residual = residualOf(effects, data, c, free, targets[c]);
    channel.variance = std::max(1e-24, residual.squaredNorm() / static_cast<double>(residual.size()));
    channels.push_back(std::move(channel));
  }
  const Eigen::Index total = unknowns + parameters;
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(parameters);
  NormalEquations stacked;
  LinearSolution solution;
  for (int iteration = 0; iteration < 50; ++iteration) {
    stacked.gram = Eigen::MatrixXd::Zero(total, total);
    stacked.moment = Eigen::VectorXd::Zero(total);
    stacked.squares = 0.0;
    stacked.samples = 0;
    for (const auto& channel : channels) {
      const double gain = driveGain(effects, gainEffect, channel.index);
      Eigen::MatrixXd columns(channel.design.rows(), channel.design.cols() + parameters);
      columns << channel.design, gain * channel.payload;
      Eigen::VectorXd target = targets[channel.index];
      if (gainFree) {
        columns.col(channel.gainColumn) += channel.payload * theta;
        target += gain * (channel.payload * theta);
      }
      const NormalEquations own = NormalEquations::of(columns, target);
      const double weight = 1.0 / channel.variance;
      const Eigen::Index p = channel.design.cols();
      stacked.gram.block(channel.offset, channel.offset, p, p) += weight * own.gram.topLeftCorner(p, p);
      stacked.gram.block(channel.offset, unknowns, p, parameters) += weight * own.gram.topRightCorner(p, parameters);
      stacked.gram.block(unknowns, channel.offset, parameters, p) += weight * own.gram.bottomLeftCorner(parameters, p);
      stacked.gram.bottomRightCorner(parameters, parameters) +=
          weight * own.gram.bottomRightCorner(parameters, parameters);
      stacked.moment.segment(channel.offset, p) += weight * own.moment.head(p);
      stacked.moment.tail(parameters) += weight * own.moment.tail(parameters);
      stacked.squares += weight * own.squares;
      stacked.samples += own.samples;
    }
    solution = solveLeastSquares(stacked);
    const Eigen::VectorXd next = solution.coefficients.tail(parameters);
    const bool settled = (next - theta).norm() <= 1e-9 * std::max(1.0, next.norm());
    theta = next;
    for (auto& channel : channels) {
      const Eigen::Index p = channel.design.cols();
      assignCoefficients(effects, channel.index, free, solution.coefficients.segment(channel.offset, p),
                         solution.standardErrors.segment(channel.offset, p));
      const double gain = driveGain(effects, gainEffect, channel.index);
      const Eigen::VectorXd residual =
          residualOf(effects, data, channel.index, free, targets[channel.index]) - gain * (channel.payload * theta);
      channel.variance = std::max(1e-24, residual.squaredNorm() / static_cast<double>(residual.size()));
    }
    if (settled) break;
  }
  // Covariance of θ: σ²·(stacked gram)⁻¹, σ² from the weighted residuals (≈ 1 when the model fits).
  double weightedSquares = 0.0;
  for (const auto& channel : channels) weightedSquares += static_cast<double>(channel.design.rows());
  const double scale =
      weightedSquares / static_cast<double>(std::max<Eigen::Index>(1, stacked.samples - solution.rank));
  const Eigen::MatrixXd inverse = stacked.gram.ldlt().solve(Eigen::MatrixXd::Identity(total, total));
  shared.shared = theta;
  shared.sharedCovariance = scale * inverse.bottomRightCorner(parameters, parameters);
  for (const auto& channel : channels) {
    const double gain = driveGain(effects, gainEffect, channel.index);
    shared.values[channel.index] = gain * theta;
    shared.standardErrors[channel.index] = std::abs(gain) * shared.sharedCovariance.diagonal().cwiseSqrt();
  }
}

// Fits every effect not marked `fixed` (fixed ones keep their values).
void fitFree(FittedModel& model, const Dataset& data, const std::vector<bool>& fixed) {
  auto& effects = model.effects;
  const std::size_t count = effects.size();
  std::vector<Eigen::VectorXd> targets;
  for (int c = 0; c < data.channelCount(); ++c) {
    Eigen::VectorXd target = data.measured(c) - data.basePrediction(c);
    for (std::size_t e = 0; e < count; ++e) {
      if (fixed[e] && effects[e].applied[c]) target -= contribution(effects[e], data, c);
    }
    targets.push_back(std::move(target));
  }
  std::vector<bool> free(count);
  for (std::size_t e = 0; e < count; ++e) free[e] = !fixed[e] && !effects[e].effect->sharedAcrossChannels();
  fitChannels(effects, data, free, targets);
  for (std::size_t e = 0; e < count; ++e) {
    if (!fixed[e] && effects[e].effect->sharedAcrossChannels()) fitShared(effects, e, data, free, targets);
  }
}

// A searched parameter stored in the model file (found when the effect was added) stays, so a
// later effect does not move an earlier one's frequency or rate (see extendModel in fitting.h).
void keepStoredNonlinear(EffectFit& fit, const EffectSpec& spec, const Dataset& data) {
  const auto nonlinear = fit.effect->nonlinearParameter();
  if (!nonlinear) return;
  const auto stored = spec.parameters.find(nonlinear->name);
  if (stored == spec.parameters.end()) return;
  if (static_cast<int>(stored->second.size()) != data.channelCount()) {
    throw Error(spec.id + ": mismatched joint count: parameter '" + nonlinear->name + "' has " +
                std::to_string(stored->second.size()) + " values but " + data.source() + " has " +
                std::to_string(data.channelCount()) + " channels");
  }
  for (int c = 0; c < data.channelCount(); ++c) {
    if (fit.applied[static_cast<std::size_t>(c)]) fit.nonlinear[static_cast<std::size_t>(c)] = stored->second[c];
  }
}

}  // namespace

std::vector<EffectFit> prepareEffects(const ModelSpec& spec, const Dataset& data) {
  if (spec.joints > 0 && spec.joints != data.channelCount()) {
    throw Error(data.source() + ": mismatched joint count: the model (" + spec.source.string() + ") expects " +
                std::to_string(spec.joints) + " joints, the data has " + std::to_string(data.channelCount()));
  }
  std::vector<EffectFit> effects;
  for (const auto& effectSpec : spec.effects) {
    EffectFit fit;
    fit.effect = createEffect(effectSpec);
    if (!fit.effect->appliesTo(data.kind())) {
      throw Error("effect '" + effectSpec.id + "' does not apply to kind " + toString(data.kind()));
    }
    for (const auto& signal : fit.effect->requiredSignals()) {
      if (!data.hasSignal(signal)) {
        data.signal(signal, 0);  // throws with the explanation of what is missing
      }
    }
    const int channels = data.channelCount();
    fit.applied.assign(static_cast<std::size_t>(channels), effectSpec.joints.empty());
    for (int joint : effectSpec.joints) {
      if (joint >= channels) {
        throw Error("effect '" + effectSpec.id + "': joint " + std::to_string(joint) + " does not exist (" +
                    data.source() + " has " + std::to_string(channels) + " channels, 0-based)");
      }
      fit.applied[static_cast<std::size_t>(joint)] = true;
    }
    const auto count = static_cast<Eigen::Index>(fit.effect->parameterNames().size());
    fit.nonlinear.assign(static_cast<std::size_t>(channels), kNaN);
    keepStoredNonlinear(fit, effectSpec, data);
    fit.values.assign(static_cast<std::size_t>(channels), Eigen::VectorXd::Zero(count));
    fit.standardErrors.assign(static_cast<std::size_t>(channels), Eigen::VectorXd::Constant(count, kNaN));
    effects.push_back(std::move(fit));
  }
  return effects;
}

Eigen::MatrixXd designMatrix(const std::vector<EffectFit>& effects, const Dataset& data, int channel) {
  Eigen::MatrixXd columns(data.samples(channel), columnCount(effects, channel));
  Eigen::Index column = 0;
  for (const auto& fit : effects) {
    if (!fit.applied[channel]) continue;
    const auto count = static_cast<Eigen::Index>(fit.effect->parameterNames().size());
    fit.effect->regressor(data, channel, fit.nonlinear[channel], columns.middleCols(column, count));
    column += count;
  }
  return columns;
}

FittedModel fitModel(const ModelSpec& spec, const Dataset& data) {
  FittedModel model;
  model.spec = spec;
  for (int c = 0; c < data.channelCount(); ++c) model.channelNames.push_back(data.channelName(c));
  model.effects = prepareEffects(spec, data);
  fitFree(model, data, std::vector<bool>(model.effects.size(), false));
  return model;
}

FittedModel extendModel(const FittedModel& before, const std::vector<EffectSpec>& additions, const Dataset& data) {
  ModelSpec spec = specWithParameters(before);
  spec.effects.insert(spec.effects.end(), additions.begin(), additions.end());
  return fitModel(spec, data);
}

FittedModel fitAdditions(const FittedModel& kept, const std::vector<EffectSpec>& additions, const Dataset& data) {
  if (kept.channelCount() != data.channelCount()) {
    throw Error(data.source() + ": mismatched joint count: the kept model has " + std::to_string(kept.channelCount()) +
                " channels, this data has " + std::to_string(data.channelCount()));
  }
  ModelSpec spec = kept.spec;
  spec.effects.insert(spec.effects.end(), additions.begin(), additions.end());
  FittedModel model;
  model.spec = spec;
  model.channelNames = kept.channelNames;
  model.effects = prepareEffects(spec, data);
  std::vector<bool> fixed(model.effects.size(), false);
  for (std::size_t e = 0; e < kept.effects.size(); ++e) {
    model.effects[e] = kept.effects[e];
    fixed[e] = true;
  }
  fitFree(model, data, fixed);
  return model;
}

FittedModel modelFromParameters(const ModelSpec& spec, const Dataset& data, bool typicalWhenMissing) {
  FittedModel model;
  model.spec = spec;
  for (int c = 0; c < data.channelCount(); ++c) model.channelNames.push_back(data.channelName(c));
  model.effects = prepareEffects(spec, data);
  for (std::size_t e = 0; e < model.effects.size(); ++e) {
    auto& fit = model.effects[e];
    const auto& stored = spec.effects[e].parameters;
    const auto names = fit.effect->parameterNames();
    const auto nonlinear = fit.effect->nonlinearParameter();
    auto valueOf = [&](const std::string& name, int c, double typicalValue) {
      const auto it = stored.find(name);
      if (it == stored.end()) {
        if (!typicalWhenMissing) {
          throw Error(spec.source.string() + ": effects[" + std::to_string(e) + "] (" + fit.effect->id() +
                      "): parameters." + name +
                      ": missing; the model has no fitted parameters to keep (fit it with "
                      "--save first)");
        }
        return typicalValue;
      }
      if (static_cast<int>(it->second.size()) != data.channelCount()) {
        throw Error(spec.source.string() + ": effect '" + fit.effect->id() + "': mismatched joint count: parameter '" +
                    name + "' has " + std::to_string(it->second.size()) + " values but " + data.source() + " has " +
                    std::to_string(data.channelCount()) + " channels");
      }
      return it->second[static_cast<std::size_t>(c)];
    };
    for (int c = 0; c < data.channelCount(); ++c) {
      if (!fit.applied[c]) continue;
      const auto typicalValues = fit.effect->typicalParameters(data.kind(), c);
      for (std::size_t p = 0; p < names.size(); ++p) {
        const double value = valueOf(names[p], c, typicalValues[p]);
        fit.values[c][static_cast<Eigen::Index>(p)] = std::isnan(value) ? 0.0 : value;
      }
      if (nonlinear) {
        const double fixed = fit.effect->option(nonlinear->name).value_or(fit.effect->typicalNonlinear(c));
        fit.nonlinear[c] = stored.count(nonlinear->name) ? valueOf(nonlinear->name, c, fixed) : fixed;
      }
    }
  }
  return model;
}

Eigen::VectorXd predict(const FittedModel& model, const Dataset& data, int channel) {
  Eigen::VectorXd prediction = data.basePrediction(channel);
  for (const auto& fit : model.effects) {
    if (!fit.applied[channel]) continue;
    Eigen::MatrixXd columns(data.samples(channel), static_cast<Eigen::Index>(fit.effect->parameterNames().size()));
    fit.effect->regressor(data, channel, fit.nonlinear[channel], columns);
    prediction += columns * fit.values[channel];
  }
  return prediction;
}

std::vector<Eigen::VectorXd> predictAll(const FittedModel& model, const Dataset& data) {
  if (data.channelCount() != model.channelCount()) {
    throw Error(data.source() + ": mismatched joint count: the model was fitted on " +
                std::to_string(model.channelCount()) + " channels, this data has " +
                std::to_string(data.channelCount()));
  }
  std::vector<Eigen::VectorXd> predictions;
  for (int c = 0; c < data.channelCount(); ++c) predictions.push_back(predict(model, data, c));
  return predictions;
}

ModelSpec specWithParameters(const FittedModel& model) {
  ModelSpec spec = model.spec;
  for (std::size_t e = 0; e < model.effects.size(); ++e) {
    const auto& fit = model.effects[e];
    auto& target = spec.effects[e];
    target.parameters.clear();
    target.standardErrors.clear();
    const auto names = fit.effect->parameterNames();
    const int channels = model.channelCount();
    for (std::size_t p = 0; p < names.size(); ++p) {
      auto& values = target.parameters[names[p]];
      auto& errors = target.standardErrors[names[p]];
      for (int c = 0; c < channels; ++c) {
        values.push_back(fit.applied[c] ? fit.values[c][static_cast<Eigen::Index>(p)] : kNaN);
        errors.push_back(fit.applied[c] ? fit.standardErrors[c][static_cast<Eigen::Index>(p)] : kNaN);
      }
    }
    if (const auto nonlinear = fit.effect->nonlinearParameter()) {
      auto& values = target.parameters[nonlinear->name];
      for (int c = 0; c < channels; ++c) values.push_back(fit.applied[c] ? fit.nonlinear[c] : kNaN);
    }
  }
  return spec;
}

}  // namespace arcplan::model
