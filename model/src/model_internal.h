#pragma once
// Declarations shared between the model module's source files and not part of its public API:
// the ordered catalogue table, effect factories defined in their own files, typical UR10e values,
// the held-out scorer of the diagnosis, and the diagnosis wording (report code).
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "arcplan/model/dataset.h"
#include "arcplan/model/diagnose.h"
#include "arcplan/model/effect.h"
#include "arcplan/model/fitting.h"

namespace arcplan::model::detail {

// The built-in catalogue, in the order docs/model.md lists it (and ties in the diagnosis keep).
struct CatalogueEntry {
  std::string id;
  EffectFactory factory;
};
const std::vector<CatalogueEntry>& catalogueTable();

EffectFactory positionRippleFactory();
EffectFactory payloadFactory();
EffectFactory dahlFrictionFactory();
EffectFactory maxwellSlipFrictionFactory();
std::unique_ptr<Effect> makeExpressionEffect(const EffectSpec& spec);

// Per-joint typical UR10e values (joints beyond the sixth reuse the last one), used by
// `arcplan model simulate` when a model file gives no parameters.
double typicalDriveGain(int channel);  // A/(N·m)
double typicalCoulomb(int channel);    // A
double typicalViscous(int channel);    // A·s/rad

// sgn(qd) as every friction term smooths it: tanh(qd / velocity_smoothing).
double smoothedDirection(const Dataset& data, double velocity);

// Per sample of a channel (`samples` long), whether a run begins there: sample 0 and every
// Dataset::runStarts() entry. Effects with a state along the log start it afresh there.
std::vector<bool> runBeginnings(const Dataset& data, Eigen::Index samples);

// Held-out sums of squares of one channel: a fixed design fitted on the training data, alone or
// with extra columns, and scored on the validation data or by cross-validation (contiguous blocks
// for logs, interleaved folds for data without time).
class HeldOutScorer {
public:
  HeldOutScorer(const Dataset& data, const Dataset* validation, Eigen::VectorXd targetTrain,
                Eigen::VectorXd targetValidation, Eigen::MatrixXd baseTrain, Eigen::MatrixXd baseValidation, int folds);

  Eigen::Index heldOutSamples() const;
  // Held-out RSS and the rank of the fit with the extra columns appended (extraValidation is
  // ignored without validation data); optionally the held-out residual itself.
  std::pair<double, int> score(const Eigen::MatrixXd& extraTrain, const Eigen::MatrixXd& extraValidation,
                               Eigen::VectorXd* heldOutResidual = nullptr) const;

private:
  bool validation_;
  Eigen::VectorXd targetTrain_, targetValidation_;
  Eigen::MatrixXd baseTrain_, baseValidation_;
  std::vector<std::vector<Eigen::Index>> members_;  // cross-validation folds
};

// ΔIC = n·ln(RSS_with / RSS_without) + k·ln(n): negative when the added parameters pay off.
double informationCriterion(double squaresWith, double squaresWithout, int addedParameters, double samples);

// Per channel, the held-out error of the model as it is, and what candidates are judged against.
struct HeldOutBaseline {
  std::vector<HeldOutScorer> scorers;
  std::vector<double> squares;
  std::vector<int> rank;
  std::vector<Eigen::MatrixXd> trainBasis;  // orthonormal span of the model's own columns (none when kept)
  std::vector<Eigen::VectorXd> trainResidual, heldOutResidual;
  // With validation data: checkProposal with the model as it is (empty without: cross-validation).
  std::function<void(EffectCandidate&)> checkStep;
  double total() const;
};

// Fills channelReduction, joints (ΔIC < 0 and at least `minimumReduction` of the channel's
// held-out RMS), score, suggested and heldoutReduction (pooled over channels) from the candidate's
// held-out squares and ranks per channel; `searched` counts a searched nonlinear parameter.
void judgeCandidate(EffectCandidate& candidate, const std::vector<double>& squares, const std::vector<int>& ranks,
                    bool searched, const HeldOutBaseline& baseline, double minimumReduction);

// Runs the step a suggested candidate proposes (extendModel, or fitAdditions with kept parameters,
// on `data`) and keeps the candidate only on the channels whose held-out RMSE on `validation` it
// lowers by at least `minimumReduction`; channelReduction (on its joints) and heldoutReduction
// become the step's own (proposal_check.cpp).
void checkProposal(EffectCandidate& candidate, const FittedModel& base, bool keepParameters, const Dataset& data,
                   const Dataset& validation, double minimumReduction);

// Library terms (term_library.h) that explain the held-out residual, as candidates (discovery.cpp).
std::vector<EffectCandidate> discoverTerms(const Dataset& data, const Dataset* validation,
                                           const HeldOutBaseline& baseline, const DiagnoseOptions& options);

// The white-noise level of a residual from its second differences (var(r[k+1] - 2r[k] + r[k-1])
// = 6σ² for white noise; a smooth model error hardly contributes at a robot log's sample rate).
double noiseFloor(const Eigen::VectorXd& residual);

// Diagnosis wording (diagnosis_text.cpp).
std::string percentText(double fraction);
std::string explainCandidate(const Effect& effect, const EffectCandidate& candidate, const Dataset& data);
// `words` says what the term follows, `picture` (may be empty) the physical picture it fits.
std::string explainDiscovery(const EffectCandidate& candidate, const std::string& words, const std::string& picture,
                             const Dataset& data);
std::string diagnosisSummary(const Diagnosis& diagnosis, double minimumReduction);

}  // namespace arcplan::model::detail
