#pragma once
// The steps of the model loop as the command line runs them (docs/model.md), reusable from C++:
// load the data a model needs, add effects and refit with before/after errors, and keep a session
// history of the error after every step.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "arcplan/model/compare.h"
#include "arcplan/model/dataset.h"
#include "arcplan/model/events.h"
#include "arcplan/model/fitting.h"
#include "arcplan/model/measurements.h"
#include "arcplan/model/model_spec.h"

namespace arcplan::model {

struct DataFiles {
  std::filesystem::path data;
  std::filesystem::path validation;  // empty: none
  LogReadOptions dataOptions, validationOptions;
  // Further runs of the same robot, joined after `data` / `validation` (joinRuns in dataset.h).
  std::vector<std::filesystem::path> moreData, moreValidation;
};

struct LoadedData {
  Dataset data;
  std::optional<Dataset> validation;
  const Dataset* validationOrNull() const { return validation ? &*validation : nullptr; }
};

// Reads both files (and their further runs) for the model's kind; the validation data must have the
// data's channel count.
LoadedData loadData(const ModelSpec& spec, const DataFiles& files);

// The same from logs already read or built in memory (makeLog): several logs of `data` (and of
// `validation`) are runs of one robot, joined end to end. Joint kinds only.
LoadedData prepareData(const ModelSpec& spec, const std::vector<Log>& data, const std::vector<Log>& validation);

// Throws arcplan::Error naming the model file when `loaded` was prepared for other settings than the model's (kind,
// load torque, robot, derivative filter, ...: everything but the effects), so data and model go together.
void checkPreparedFor(const LoadedData& loaded, const ModelSpec& spec);

// The model `compare` judges: fitted to `data`, or with `keepParameters` the parameters stored in the spec.
FittedModel comparedModel(const ModelSpec& spec, const Dataset& data, bool keepParameters);

struct FitStep {
  std::vector<std::string> added;  // "load_friction:1,2"
  FittedModel before, after;
  ErrorSummary beforeData, afterData;
  std::optional<ErrorSummary> beforeValidation, afterValidation;
  // Moments left out of the fit and of the errors (events of the model before the step), per log.
  std::vector<Event> dataEvents, validationEvents;
};

// Adds the effects to the model (each must be new and apply to its kind), refits on `data`, and
// reports the errors before and after on both datasets. The step is extendModel (fitting.h) on the
// samples diagnose scores on (leaveOutEvents, events.h; `leaveOutEvents` false: every sample), so
// it is the step the diagnosis proposed. With `keepParameters` the model's stored parameters stay
// fixed (before = the model as saved) and only the additions are fitted.
FitStep addEffectsAndFit(const ModelSpec& spec, const std::vector<EffectSpec>& additions, const Dataset& data,
                         const Dataset* validation, bool keepParameters = false, bool leaveOutEvents = true);

std::string describeEffect(const EffectSpec& effect);  // "coulomb", "load_friction:1,2"

// One row of the session history (`arcplan model history`).
struct SessionStep {
  std::string command;               // "compare", "fit +load_friction:1,2"
  std::vector<std::string> effects;  // the model's effects after the step
  ErrorSummary data;
  std::optional<ErrorSummary> validation;
};

// The session step of a comparison ("compare") and of a fit ("fit +load_friction:1,2").
SessionStep comparisonStep(const ModelSpec& spec, const Comparison& comparison);
SessionStep fitSessionStep(const FitStep& step);

// The history kept in a session file (JSON); a missing file is an empty history. Appending
// rewrites the file atomically.
std::vector<SessionStep> readSession(const std::filesystem::path& file);
void appendSessionStep(const std::filesystem::path& file, const SessionStep& step);

}  // namespace arcplan::model
