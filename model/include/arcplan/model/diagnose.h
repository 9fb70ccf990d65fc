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
//
// Discovery beyond the catalogue (joint logs): every term of the library in term_library.h is
// screened on the training residual (the share of it the term explains beyond the model's own
// columns), the best few per channel are scored on held-out data by the same rule, and each
// becomes a candidate that applies the one term to the channels where it passes. A discovered
// term ranks above a catalogue effect only when it leaves at least 1 % less held-out residual RMS
// (a catalogue effect names the physics; a new term must explain clearly more to come first: on
// a 20 s log at 250 Hz, 1 % of RMS is a held-out ΔIC of about -100 in the new term's favour).
// How much could be explained at all: the noise floor of each channel's held-out residual from
// its second differences (white noise), compared with the catalogue's suggestions together.
//
// With `keepParameters` the model's stored parameters stay fixed (a model fitted on another log):
// every candidate is fitted and scored on what that model leaves.
//
// Events (events.h: a push, a collision) are not effects: with `leaveOutEvents` the events of the
// model's residual on both logs are found first and their samples left out of every fit and
// score, and the summary says so.
#include <optional>
#include <string>
#include <vector>

#include "arcplan/model/compare.h"
#include "arcplan/model/dataset.h"
#include "arcplan/model/effect.h"
#include "arcplan/model/events.h"
#include "arcplan/model/model_spec.h"

namespace arcplan::model {

struct DiagnoseOptions {
  int folds = 5;                        // cross-validation folds when there is no validation data
  double minimumReduction = 0.01;       // per channel, fraction of the held-out residual RMS
  std::vector<std::string> candidates;  // empty: every registered effect not in the model
  bool discover = true;                 // also search the term library (joint logs)
  int screenedPerChannel = 6;           // library terms per channel scored on held-out data
  bool keepParameters = false;          // the model's stored parameters stay fixed
  bool leaveOutEvents = true;           // score without the events of the model's residual (events.h)
};

struct EffectCandidate {
  std::string effect;             // catalogue id, or the id of a discovered term
  bool discovered = false;        // a library term, not a registered effect
  EffectSpec entry;               // what to add: id, joints and (discovered) the expression
  std::string modelEntry;         // the same as a model-file line: {id: ..., expression: "...", joints: [...]}
  std::vector<int> joints;        // channels where it helps significantly
  double heldoutReduction = 0.0;  // fraction (0–1) of the held-out residual RMS removed
  double score = 0.0;             // Σ ΔIC over its channels (negative: better)
  bool suggested = false;
  std::vector<double> channelReduction;  // per channel, fraction of that channel's held-out RMS
  std::vector<double> nonlinear;         // searched value per channel (NaN if none)
  std::string nonlinearName, nonlinearUnit;
  std::vector<PhysicalQuantity> quantities;  // shared effects (payload): fitted jointly, physical units
  std::string explanation;
};

struct Diagnosis {
  std::string heldout;                   // "validation data (V.csv)" or "5-fold time-blocked cross-validation"
  ErrorSummary heldoutBase;              // held-out error of the model as it is
  std::vector<EffectCandidate> ranking;  // suggested first (best first), then the rest
  std::vector<std::string> skipped;      // "temperature_friction: the log has no joint_temperatures"
  std::vector<ResidualCorrelation> residualFollows;  // what the held-out residual still correlates with
  std::vector<double> noiseFloor;                    // per channel, of the held-out residual (NaN without time)
  double explainable = 0.0;                          // fraction of the held-out residual RMS above the noise floor
  double catalogueExplains = 0.0;                    // fraction the suggested catalogue effects remove together
  std::string summary;                               // the top suggestions in words, or why nothing is suggested
  // Moments left out before anything was fitted or scored (events of the model as it is), per log.
  std::vector<Event> dataEvents, validationEvents;
};

// Throws Error unless the options' numbers are usable (checkFolds, checkMinimumReduction).
Diagnosis diagnose(const ModelSpec& spec, const Dataset& data, const Dataset* validation,
                   const DiagnoseOptions& options = {});

// The limits of DiagnoseOptions' numbers, one owner for diagnose(), the command line and Python, so
// a wrong value is refused, never clamped. `name` is the caller's spelling (--folds, folds) for the
// message "<name> must be ..., got <value>" (Error).
// folds: an integer >= 2 (one fold is held out while the others are fitted).
void checkFolds(int folds, const std::string& name);
// minimumReduction: a fraction in [0, 1] (a negative one would keep effects that add error).
void checkMinimumReduction(double fraction, const std::string& name);

// "joints 1–2", "joint 3", "joints 0, 2 and 5"; channel names for gearbox data.
std::string describeChannels(const Dataset& data, const std::vector<int>& channels);

}  // namespace arcplan::model
