#pragma once
// Machine-readable (JSON, described in docs/model.md) and human-readable (text tables) forms of
// the model loop's results.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arcplan/model/compare.h"
#include "arcplan/model/diagnose.h"
#include "arcplan/model/events.h"
#include "arcplan/model/fitting.h"
#include "arcplan/model/workflow.h"

namespace arcplan::model {

// {channels: {name: {rmse, nrmse, r2}}, overall_nrmse}
nlohmann::json toJson(const ErrorSummary& summary);
// channel -> effect -> {parameter: {value, standard_error}, nonlinear parameter: value}; effects
// fitted jointly across channels add their physical quantities (payload: mass_kg, center_of_mass_m).
nlohmann::json parametersJson(const FittedModel& model);
// [{start_s, end_s, joints, peak, peak_scales, wrench_N, wrench_fit}] (wrench null where the arm is not known)
nlohmann::json toJson(const std::vector<Event>& events);
// compare: channels, overall_nrmse, validation, worst_windows, events, regimes, residual_follows, parameters
nlohmann::json toJson(const Comparison& comparison, const FittedModel& model, const Dataset& data);
// diagnose: ranking [{effect, joints, heldout_reduction, score, explanation, ...}], summary, ...
nlohmann::json toJson(const Diagnosis& diagnosis);
// fit: added, before/after {train, validation} with overall_nrmse and per-channel rmse
nlohmann::json toJson(const FitStep& step);
nlohmann::json toJson(const std::vector<SessionStep>& history);
SessionStep sessionStepFromJson(const nlohmann::json& json);

std::string formatDataQuality(const Dataset& data);
std::string formatErrors(const ErrorSummary& data, const ErrorSummary* validation);
std::string formatParameters(const FittedModel& model);
std::string formatEvents(const std::vector<Event>& events);
std::string formatComparison(const Comparison& comparison);
std::string formatDiagnosis(const Diagnosis& diagnosis);
std::string formatFitStep(const FitStep& step);
std::string formatHistory(const std::vector<SessionStep>& history);

}  // namespace arcplan::model
