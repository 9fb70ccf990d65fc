#include "arcplan/model/fitting.h"

#include <cmath>
#include <limits>

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

// Least squares of the applied effects (only those with `include`) on one channel.
LinearSolution solveChannel(std::vector<EffectFit>& effects, const Dataset& data, int channel,
                            const std::vector<bool>& include) {
  std::vector<EffectFit> subset;
  for (std::size_t e = 0; e < effects.size(); ++e) {
    if (include[e]) subset.push_back(effects[e]);
  }
  const Eigen::MatrixXd columns = designMatrix(subset, data, channel);
  const Eigen::VectorXd target = data.measured(channel) - data.basePrediction(channel);
  const LinearSolution solution = solveLeastSquares(NormalEquations::of(columns, target));
  Eigen::Index column = 0;
  for (std::size_t e = 0; e < effects.size(); ++e) {
    if (!include[e] || !effects[e].applied[channel]) continue;
    const auto count = static_cast<Eigen::Index>(effects[e].effect->parameterNames().size());
    effects[e].values[channel] = solution.coefficients.segment(column, count);
    effects[e].standardErrors[channel] = solution.standardErrors.segment(column, count);
    column += count;
  }
  return solution;
}

Eigen::VectorXd residualOf(const std::vector<EffectFit>& effects, const Dataset& data, int channel,
                           const std::vector<bool>& include) {
  Eigen::VectorXd residual = data.measured(channel) - data.basePrediction(channel);
  for (std::size_t e = 0; e < effects.size(); ++e) {
    if (!include[e] || !effects[e].applied[channel]) continue;
    Eigen::MatrixXd columns(data.samples(channel), static_cast<Eigen::Index>(effects[e].effect->parameterNames().size()));
    effects[e].effect->regressor(data, channel, effects[e].nonlinear[channel], columns);
    residual -= columns * effects[e].values[channel];
  }
  return residual;
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
  auto& effects = model.effects;
  const std::size_t count = effects.size();
  for (int c = 0; c < data.channelCount(); ++c) {
    // Linear effects first; each nonlinear effect then searches its parameter on what the others
    // leave, twice round so that two nonlinear effects settle against each other.
    std::vector<bool> include(count);
    for (std::size_t e = 0; e < count; ++e) include[e] = !effects[e].effect->nonlinearParameter().has_value();
    std::vector<std::size_t> nonlinear;
    for (std::size_t e = 0; e < count; ++e) {
      if (!include[e] && effects[e].applied[c]) nonlinear.push_back(e);
    }
    for (int round = 0; round < (nonlinear.size() > 1 ? 2 : 1); ++round) {
      for (std::size_t e : nonlinear) {
        include[e] = false;
        solveChannel(effects, data, c, include);
        const Eigen::VectorXd residual = residualOf(effects, data, c, include);
        effects[e].nonlinear[c] = effects[e].effect->searchNonlinear(data, c, residual);
        include[e] = true;
      }
    }
    std::vector<bool> all(count, true);
    solveChannel(effects, data, c, all);
  }
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
          throw Error(spec.source.string() + ": effect '" + fit.effect->id() + "' has no stored parameter '" + name +
                      "' (fit and --save the model first)");
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
                std::to_string(model.channelCount()) + " channels, this data has " + std::to_string(data.channelCount()));
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
