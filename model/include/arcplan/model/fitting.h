#pragma once
// Fitting a model's effects to a dataset, channel by channel: nonlinear parameters searched on the
// residual of the other effects, then every linear parameter by one least-squares solve with
// standard errors. A FittedModel predicts any dataset of the same kind.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arcplan/model/dataset.h"
#include "arcplan/model/effect.h"
#include "arcplan/model/model_spec.h"

namespace arcplan::model {

struct EffectFit {
  std::shared_ptr<const Effect> effect;
  std::vector<bool> applied;                    // per channel
  std::vector<double> nonlinear;                // per channel; NaN for linear effects / not applied
  std::vector<Eigen::VectorXd> values;          // per channel, one entry per parameterNames()
  std::vector<Eigen::VectorXd> standardErrors;  // NaN: not identifiable on that channel (collinear)
};

struct FittedModel {
  ModelSpec spec;
  std::vector<std::string> channelNames;
  std::vector<EffectFit> effects;

  int channelCount() const { return static_cast<int>(channelNames.size()); }
};

// The effects of `spec`, checked against the dataset: each must apply to the kind, find the
// signals it reads, and name existing joints. Throws arcplan::Error otherwise.
std::vector<EffectFit> prepareEffects(const ModelSpec& spec, const Dataset& data);

// Regressor columns of the given effects on one channel (effects in order, their parameters in
// order); effects not applied on the channel contribute no columns.
Eigen::MatrixXd designMatrix(const std::vector<EffectFit>& effects, const Dataset& data, int channel);

FittedModel fitModel(const ModelSpec& spec, const Dataset& data);

// The model with the parameters stored in the spec (a saved fit, or the truth of a simulation).
// With `typicalWhenMissing`, effects without stored values take their typical UR10e values;
// otherwise a missing value is an error.
FittedModel modelFromParameters(const ModelSpec& spec, const Dataset& data, bool typicalWhenMissing);

// base + Σ effects, for one channel / all channels.
Eigen::VectorXd predict(const FittedModel& model, const Dataset& data, int channel);
std::vector<Eigen::VectorXd> predictAll(const FittedModel& model, const Dataset& data);

// The spec with the fitted values written into each effect's `parameters` / `standard_errors`.
ModelSpec specWithParameters(const FittedModel& model);

}  // namespace arcplan::model
