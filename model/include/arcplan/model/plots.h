#pragma once
// Figures of the model loop (PNG, matplotlib via scripts/plot/plot_model_*.py). The numbers go to
// CSV/JSON files next to the figures so they can be re-plotted; a missing matplotlib is reported
// in the outcome, not thrown.
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arcplan/common/plotting.h"
#include "arcplan/model/dataset.h"
#include "arcplan/model/diagnose.h"
#include "arcplan/model/fitting.h"
#include "arcplan/model/workflow.h"

namespace arcplan::model {

// <prefix>_series.csv, <prefix>_measured_vs_predicted.png, <prefix>_residual_vs_signals.png;
// for gearbox data <prefix>_force_transfer.png (input vs output torque per gearbox, the model's
// lines for both directions and the ideal ratio, like the thesis' figures 2.12–2.14).
PlotOutcome plotComparison(const FittedModel& model, const Dataset& data, const std::filesystem::path& directory,
                           const std::string& prefix);

// diagnose_ranking.json + diagnose_ranking.png: held-out error reduction per candidate effect.
PlotOutcome plotDiagnosis(const Diagnosis& diagnosis, const std::filesystem::path& directory);

// fit_before_after.json + fit_before_after.png: RMSE per channel before and after, train and validation.
PlotOutcome plotFitStep(const FitStep& step, const std::filesystem::path& directory);

// history.png: overall NRMSE and per-channel RMSE after every step (the falling-error chart).
PlotOutcome plotHistory(const std::filesystem::path& sessionFile, const std::filesystem::path& directory);

}  // namespace arcplan::model
