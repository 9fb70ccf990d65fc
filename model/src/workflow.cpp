#include "arcplan/model/workflow.h"

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "arcplan/model/result_formats.h"

namespace arcplan::model {

namespace {

Dataset loadRuns(const std::filesystem::path& first, const std::vector<std::filesystem::path>& more,
                 const ModelSpec& spec, const LogReadOptions& options) {
  std::vector<Dataset> runs{loadDataset(first, spec, options)};
  for (const auto& run : more) runs.push_back(loadDataset(run, spec, options));
  return joinRuns(runs);
}

void checkChannelCounts(const LoadedData& loaded, const std::string& data, const std::string& validation) {
  if (loaded.validation && loaded.validation->channelCount() != loaded.data.channelCount()) {
    throw Error(validation + ": mismatched joint count: " + std::to_string(loaded.validation->channelCount()) +
                " channels, but " + data + " has " + std::to_string(loaded.data.channelCount()));
  }
}

Dataset joinLogs(const std::vector<Log>& logs, const ModelSpec& spec) {
  std::vector<Dataset> runs;
  for (const auto& log : logs) runs.push_back(makeJointDataset(log, spec));
  return joinRuns(runs);
}

std::vector<std::string> effectNames(const ModelSpec& spec) {
  std::vector<std::string> names;
  for (const auto& e : spec.effects) names.push_back(describeEffect(e));
  return names;
}

}  // namespace

LoadedData loadData(const ModelSpec& spec, const DataFiles& files) {
  LoadedData loaded{loadRuns(files.data, files.moreData, spec, files.dataOptions), std::nullopt};
  if (!files.validation.empty()) {
    loaded.validation = loadRuns(files.validation, files.moreValidation, spec, files.validationOptions);
    checkChannelCounts(loaded, files.data.string(), files.validation.string());
  }
  return loaded;
}

LoadedData prepareData(const ModelSpec& spec, const std::vector<Log>& data, const std::vector<Log>& validation) {
  if (data.empty()) throw Error("no data: give at least one log");
  LoadedData loaded{joinLogs(data, spec), std::nullopt};
  if (!validation.empty()) {
    loaded.validation = joinLogs(validation, spec);
    checkChannelCounts(loaded, data.front().source.string(), validation.front().source.string());
  }
  return loaded;
}

void checkPreparedFor(const LoadedData& loaded, const ModelSpec& spec) {
  const auto settings = [](ModelSpec s) {
    s.name.clear();
    s.source.clear();
    s.effects.clear();
    return toYaml(s);
  };
  if (settings(loaded.data.settings()) != settings(spec)) {
    throw Error(spec.source.string() + ": the data was prepared for a model with other settings (" +
                loaded.data.settings().source.string() +
                "); load it again with this model: only the effects may differ");
  }
}

FittedModel comparedModel(const ModelSpec& spec, const Dataset& data, bool keepParameters) {
  return keepParameters ? modelFromParameters(spec, data, false) : fitModel(spec, data);
}

std::string describeEffect(const EffectSpec& effect) {
  std::string text = effect.id;
  for (std::size_t k = 0; k < effect.joints.size(); ++k) text += (k ? "," : ":") + std::to_string(effect.joints[k]);
  return text;
}

FitStep addEffectsAndFit(const ModelSpec& spec, const std::vector<EffectSpec>& additions, const Dataset& allData,
                         const Dataset* allValidation, bool keepParameters, bool leaveOutEvents) {
  if (additions.empty()) throw Error("fit: nothing to add (use --add EFFECT[:j0,j1..])");
  ModelSpec extended = spec;
  FitStep step;
  for (const auto& addition : additions) {
    if (extended.hasEffect(addition.id)) {
      throw Error("--add " + describeEffect(addition) + ": effect '" + addition.id + "' is already in the model");
    }
    if (!createEffect(addition)->appliesTo(spec.kind)) {
      throw Error("--add " + describeEffect(addition) + ": effect '" + addition.id + "' does not apply to kind " +
                  toString(spec.kind));
    }
    extended.effects.push_back(addition);
    step.added.push_back(describeEffect(addition));
  }
  // The samples the diagnosis scores on: without the events of the model as it is.
  const FittedModel asItIs = keepParameters ? modelFromParameters(spec, allData, false) : fitModel(spec, allData);
  EventFreeData clean{&allData, allValidation, std::nullopt, std::nullopt, {}, {}};
  if (leaveOutEvents) clean = arcplan::model::leaveOutEvents(asItIs, allData, allValidation);
  const Dataset& data = clean.data();
  const Dataset* validation = clean.validation();
  step.dataEvents = clean.dataEvents;
  step.validationEvents = clean.validationEvents;
  if (keepParameters) {
    step.before = asItIs;
    step.after = fitAdditions(step.before, additions, data);
  } else {
    step.before = step.dataEvents.empty() ? asItIs : fitModel(spec, data);
    step.after = extendModel(step.before, additions, data);
  }
  step.beforeData = errorSummary(data, predictAll(step.before, data));
  step.afterData = errorSummary(data, predictAll(step.after, data));
  if (validation) {
    step.beforeValidation = errorSummary(*validation, predictAll(step.before, *validation));
    step.afterValidation = errorSummary(*validation, predictAll(step.after, *validation));
  }
  return step;
}

SessionStep comparisonStep(const ModelSpec& spec, const Comparison& comparison) {
  return {"compare", effectNames(spec), comparison.data, comparison.validation};
}

SessionStep fitSessionStep(const FitStep& step) {
  std::string command = "fit";
  for (const auto& added : step.added) command += " +" + added;
  return {command, effectNames(step.after.spec), step.afterData, step.afterValidation};
}

std::vector<SessionStep> readSession(const std::filesystem::path& file) {
  std::vector<SessionStep> steps;
  if (!std::filesystem::exists(file)) return steps;
  std::ifstream in(file);
  nlohmann::json document;
  try {
    in >> document;
    for (const auto& step : document.at("steps")) steps.push_back(sessionStepFromJson(step));
  } catch (const nlohmann::json::exception& e) {
    throw Error(file.string() + ": not an arcplan session history: " + e.what());
  }
  return steps;
}

void appendSessionStep(const std::filesystem::path& file, const SessionStep& step) {
  auto steps = readSession(file);
  steps.push_back(step);
  writeFileAtomically(file, toJson(steps).dump(2) + "\n");
}

}  // namespace arcplan::model
