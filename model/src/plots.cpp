#include "arcplan/model/plots.h"

#include <charconv>
#include <map>

#include "arcplan/common/atomic_file.h"
#include "arcplan/model/result_formats.h"

namespace arcplan::model {
namespace {

void appendNumber(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

// A plot is about a thousand pixels wide: a longer log is written as every k-th sample, which keeps the
// series file (and the plot script reading it) small for hour-long logs instead of gigabytes.
constexpr Eigen::Index kMaxSeriesSamples = 20000;

// One row per channel and sample (every k-th beyond kMaxSeriesSamples; `index` is the sample's own):
// measured, predicted, the kind's base prediction (the ideal ratio for gearbox data) and the signals a
// residual is plotted against.
void writeSeries(const FittedModel& model, const Dataset& data, const std::filesystem::path& file) {
  const auto predictions = predictAll(model, data);
  const std::vector<std::string> signals{"q", "qd", "qdd", "tau", "temperature"};
  std::string text = "channel,index,time,measured,predicted,base";
  for (const auto& s : signals) text += "," + s;
  text += "\n";
  for (int c = 0; c < data.channelCount(); ++c) {
    const auto& time = data.signal("time", c);
    const Eigen::Index samples = data.samples(c);
    const Eigen::Index stride = (samples + kMaxSeriesSamples - 1) / kMaxSeriesSamples;
    for (Eigen::Index k = 0; k < samples; k += stride) {
      text += data.channelName(c) + "," + std::to_string(k) + ",";
      appendNumber(text, time[k]);
      text += ",";
      appendNumber(text, data.measured(c)[k]);
      text += ",";
      appendNumber(text, predictions[c][k]);
      text += ",";
      appendNumber(text, data.basePrediction(c)[k]);
      for (const auto& s : signals) {
        text += ",";
        if (data.hasSignal(s)) appendNumber(text, data.signal(s, c)[k]);
      }
      text += "\n";
    }
  }
  writeFileAtomically(file, text);
}

// The fitted force-transfer lines on a fine grid of output torque, per gearbox and direction.
void writeForceTransferCurves(const FittedModel& model, const Dataset& data, const std::filesystem::path& file) {
  std::vector<ForceTransferPoint> grid;
  for (int c = 0; c < data.channelCount(); ++c) {
    const auto& tau = data.signal("tau", c);
    const auto& base = data.basePrediction(c);
    // The ideal ratio is tau / base wherever base is non-zero.
    double ratio = 0.0;
    for (Eigen::Index k = 0; k < tau.size(); ++k) {
      if (base[k] != 0.0) ratio = tau[k] / base[k];
    }
    const std::string name = data.channelName(c);
    const auto slash = name.rfind('/');
    for (int k = 0; k <= 60; ++k) {
      ForceTransferPoint p;
      p.gearbox = name.substr(0, slash);
      p.direct = name.substr(slash + 1) == "direct";
      p.ratio = ratio;
      p.outputTorque = tau.maxCoeff() * k / 60.0;
      grid.push_back(p);
    }
  }
  const Dataset curves = makeGearboxDataset(grid, model.spec, "grid");
  writeSeries(model, curves, file);
}

PlotOutcome writeJsonAndPlot(const nlohmann::json& document, const std::filesystem::path& json,
                             const std::string& script, const std::vector<std::string>& arguments) {
  writeFileAtomically(json, document.dump(2) + "\n");
  return runPlotScript(script, arguments);
}

}  // namespace

PlotOutcome plotComparison(const FittedModel& model, const Dataset& data, const std::filesystem::path& directory,
                           const std::string& prefix) {
  const auto series = directory / (prefix + "_series.csv");
  writeSeries(model, data, series);
  auto outcome = runPlotScript("plot_model_compare.py", {series.string(), (directory / prefix).string()});
  if (outcome.ok && data.kind() == ModelKind::GearboxFtd) {
    const auto curves = directory / (prefix + "_force_transfer_model.csv");
    writeForceTransferCurves(model, data, curves);
    outcome = runPlotScript("plot_model_ftd.py", {series.string(), curves.string(),
                                                  (directory / (prefix + "_force_transfer.png")).string()});
  }
  return outcome;
}

PlotOutcome plotDiagnosis(const Diagnosis& diagnosis, const std::filesystem::path& directory) {
  const auto json = directory / "diagnose_ranking.json";
  return writeJsonAndPlot(toJson(diagnosis), json, "plot_model_diagnose.py",
                          {json.string(), (directory / "diagnose_ranking.png").string()});
}

PlotOutcome plotFitStep(const FitStep& step, const std::filesystem::path& directory) {
  const auto json = directory / "fit_before_after.json";
  return writeJsonAndPlot(toJson(step), json, "plot_model_fit.py",
                          {json.string(), (directory / "fit_before_after.png").string()});
}

PlotOutcome plotHistory(const std::filesystem::path& sessionFile, const std::filesystem::path& directory) {
  return runPlotScript("plot_model_history.py", {sessionFile.string(), (directory / "history.png").string()});
}

}  // namespace arcplan::model
