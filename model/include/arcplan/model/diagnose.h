#pragma once
// Which physical effect is the model missing? Every registered effect that applies to the model's
// kind and is not in the model is fitted to the residual (nonlinear parameter searched on the
// training data) and scored on held-out data: the validation log when given, else time-blocked
// cross-validation (contiguous blocks; interleaved folds for data without time).
//
// Per channel, the effect's held-out score is an information criterion on the held-out residual,
//   ΔIC = n·ln(RSS_with / RSS_without) + k·ln(n)      (k = linear + searched parameters),
// and the effect is kept on a channel when ΔIC < 0 and it removes at least `minimumReduction` of
// that channel's held-out residual RMS. Effects are ranked by the fraction of the held-out
// residual RMS they remove on their kept channels, pooled over all channels in the channels' own
// unit (A, rad or N·m: one kind has one unit). An effect with no kept channel is not suggested.
#include <optional>
#include <string>
#include <vector>

#include "arcplan/model/compare.h"
#include "arcplan/model/dataset.h"
#include "arcplan/model/model_spec.h"

namespace arcplan::model {

struct DiagnoseOptions {
  int folds = 5;                   // cross-validation folds when there is no validation data
  double minimumReduction = 0.01;  // per channel, fraction of the held-out residual RMS
  std::vector<std::string> candidates;  // empty: every registered effect not in the model
};

struct EffectCandidate {
  std::string effect;
  std::vector<int> joints;            // channels where it helps significantly
  double heldoutReduction = 0.0;      // fraction (0–1) of the held-out residual RMS removed
  double score = 0.0;                 // Σ ΔIC over its channels (negative: better)
  bool suggested = false;
  std::vector<double> channelReduction;  // per channel, fraction of that channel's held-out RMS
  std::vector<double> nonlinear;         // searched value per channel (NaN if none)
  std::string nonlinearName, nonlinearUnit;
  std::string explanation;
};

struct Diagnosis {
  std::string heldout;  // "validation data (V.csv)" or "5-fold time-blocked cross-validation"
  ErrorSummary heldoutBase;  // held-out error of the model as it is
  std::vector<EffectCandidate> ranking;  // suggested first (best first), then the rest
  std::vector<std::string> skipped;      // "temperature_friction: the log has no joint_temperatures"
  std::vector<ResidualCorrelation> residualFollows;  // what the held-out residual still correlates with
  std::string summary;  // the top suggestions in words, or why nothing is suggested
};

Diagnosis diagnose(const ModelSpec& spec, const Dataset& data, const Dataset* validation,
                   const DiagnoseOptions& options = {});

// "joints 1–2", "joint 3", "joints 0, 2 and 5"; channel names for gearbox data.
std::string describeChannels(const Dataset& data, const std::vector<int>& channels);

}  // namespace arcplan::model
