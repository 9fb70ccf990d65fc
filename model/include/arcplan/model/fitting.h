#pragma once
// Fitting a model's effects to a dataset, channel by channel: nonlinear parameters searched on the
// residual of the other effects, then every linear parameter by one least-squares solve with
// standard errors. Effects with physical parameters of the whole arm (a payload: one mass and
// centre of mass) are fitted jointly across channels by alternating least squares: the
// per-channel effects on what the shared term leaves, the shared parameters on all channels
// stacked (each seen through its channel's fitted drive gain, each channel weighted by the inverse
// of its residual RMS), until the shared parameters settle. A FittedModel predicts any dataset of
// the same kind.
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
  // Effects shared across channels: the one parameter vector θ (physical units) and its
  // covariance; values[c] = drive gain of c · θ. Empty otherwise, and for parameters read from a file.
  Eigen::VectorXd shared;
  Eigen::MatrixXd sharedCovariance;
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

// Every parameter of `spec` fitted to the data, except searched (nonlinear) parameters stored in
// the spec, which stay: they were found when their effect was added to the model.
FittedModel fitModel(const ModelSpec& spec, const Dataset& data);

// One step of the model loop (fit --add, and the diagnosis' check of what it proposes): `before`
// with the additions, every linear parameter refitted, the searched parameters of before's
// effects kept and the additions' searched. The diagnosis scores an addition against the model's
// own columns as they are; re-searching them would make the step another model than the one
// scored (on the real UR5 runs, joint 0's ripple moved from 86 to 6 cycles per revolution when
// Dahl friction was added: closer on the training runs, 16 % worse held out).
FittedModel extendModel(const FittedModel& before, const std::vector<EffectSpec>& additions, const Dataset& data);

// `kept` (a model with its parameters, e.g. read with modelFromParameters) stays fixed; only the
// additions are fitted to what it leaves of `data` (`--keep-parameters` of fit). Shared effects
// among the additions use the kept drive gains.
FittedModel fitAdditions(const FittedModel& kept, const std::vector<EffectSpec>& additions, const Dataset& data);

// The model with the parameters stored in the spec (a saved fit, or the truth of a simulation).
// With `typicalWhenMissing`, effects without stored values take their typical UR10e values;
// otherwise a missing value is an error that names the model file, the effect and the parameter.
FittedModel modelFromParameters(const ModelSpec& spec, const Dataset& data, bool typicalWhenMissing);

// base + Σ effects, for one channel / all channels.
Eigen::VectorXd predict(const FittedModel& model, const Dataset& data, int channel);
std::vector<Eigen::VectorXd> predictAll(const FittedModel& model, const Dataset& data);

// The spec with the fitted values written into each effect's `parameters` / `standard_errors`.
ModelSpec specWithParameters(const FittedModel& model);

}  // namespace arcplan::model
