// The JSON and text forms of every result of the model loop, in one place so each format has one
// owner (a little over 400 lines for that reason).
#include "arcplan/model/result_formats.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace arcplan::model {
namespace {

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), pattern, value);
  return buffer;
}

std::string padded(const std::string& text, std::size_t width) {
  return text.size() >= width ? text + " " : text + std::string(width - text.size(), ' ');
}

nlohmann::json rmseOnly(const ErrorSummary& summary) {
  nlohmann::json channels = nlohmann::json::object();
  for (const auto& c : summary.channels) channels[c.channel] = {{"rmse", c.rmse}};
  return {{"overall_nrmse", summary.overallNrmse}, {"channels", channels}};
}

// One value, or a vector for a vector quantity (the centre of mass).
nlohmann::json quantityJson(const PhysicalQuantity& quantity) {
  if (quantity.values.size() == 1)
    return {{"value", quantity.values[0]}, {"standard_error", quantity.standardErrors[0]}};
  return {{"value", quantity.values}, {"standard_error", quantity.standardErrors}};
}

std::string quantityText(const PhysicalQuantity& quantity) {
  std::string values, errors;
  for (std::size_t i = 0; i < quantity.values.size(); ++i) {
    values += (i ? ", " : "") + format("%.5g", quantity.values[i]);
    errors += (i ? ", " : "") + format("%.2g", quantity.standardErrors[i]);
  }
  return quantity.values.size() == 1 ? quantity.name + " = " + values + " ± " + errors
                                     : quantity.name + " = (" + values + ") ± (" + errors + ")";
}

ErrorSummary summaryFromJson(const nlohmann::json& json) {
  ErrorSummary summary;
  summary.overallNrmse = json.at("overall_nrmse").get<double>();
  for (const auto& [name, values] : json.at("channels").items()) {
    ChannelError error;
    error.channel = name;
    error.rmse = values.at("rmse").get<double>();
    error.nrmse = values.value("nrmse", 0.0);
    error.r2 = values.value("r2", 0.0);
    error.samples = values.value("samples", Eigen::Index{0});
    summary.channels.push_back(error);
  }
  return summary;
}

}  // namespace

nlohmann::json toJson(const std::vector<Event>& events) {
  nlohmann::json result = nlohmann::json::array();
  for (const auto& e : events) {
    nlohmann::json wrench = nullptr;
    if (e.wrench) wrench = {e.wrench->x(), e.wrench->y(), e.wrench->z()};
    result.push_back({{"start_s", e.start},
                      {"end_s", e.end},
                      {"joints", e.joints},
                      {"peak", e.peak},
                      {"peak_scales", e.peakScales},
                      {"wrench_N", wrench},
                      {"wrench_fit", e.wrench ? nlohmann::json(e.wrenchFit) : nlohmann::json(nullptr)}});
  }
  return result;
}

std::string formatEvents(const std::vector<Event>& events) {
  if (events.empty()) return "none: the residual stays within its noise band\n";
  std::ostringstream text;
  for (const auto& e : events) {
    std::string joints, peaks;
    for (std::size_t k = 0; k < e.joints.size(); ++k) {
      joints += (k ? "," : "") + std::to_string(e.joints[k]);
      peaks += (k ? ", " : "") + format("%.3g", e.peak[k]);
    }
    text << "  " << format("%.3f", e.start) << " .. " << format("%.3f", e.end) << " s  joints " << joints << "  peak "
         << peaks << " (" << format("%.1f", e.peakScales) << " noise scales)";
    if (e.wrench) {
      text << "  tool force (" << format("%.1f", e.wrench->x()) << ", " << format("%.1f", e.wrench->y()) << ", "
           << format("%.1f", e.wrench->z()) << ") N, |f| = " << format("%.1f", e.wrench->norm()) << " N";
    }
    text << "\n";
  }
  return text.str();
}

nlohmann::json toJson(const ErrorSummary& summary) {
  nlohmann::json channels = nlohmann::json::object();
  for (const auto& c : summary.channels) {
    channels[c.channel] = {{"rmse", c.rmse}, {"nrmse", c.nrmse}, {"r2", c.r2}, {"samples", c.samples}};
  }
  return {{"channels", channels}, {"overall_nrmse", summary.overallNrmse}};
}

nlohmann::json parametersJson(const FittedModel& model) {
  nlohmann::json result = nlohmann::json::object();
  for (int c = 0; c < model.channelCount(); ++c) {
    nlohmann::json channel = nlohmann::json::object();
    for (const auto& fit : model.effects) {
      if (!fit.applied[c]) continue;
      nlohmann::json effect = nlohmann::json::object();
      const auto names = fit.effect->parameterNames();
      for (std::size_t p = 0; p < names.size(); ++p) {
        const double error = fit.standardErrors[c][static_cast<Eigen::Index>(p)];
        effect[names[p]] = {{"value", fit.values[c][static_cast<Eigen::Index>(p)]},
                            {"standard_error", std::isnan(error) ? nlohmann::json(nullptr) : nlohmann::json(error)},
                            {"identifiable", !std::isnan(error)}};
      }
      if (const auto nonlinear = fit.effect->nonlinearParameter()) effect[nonlinear->name] = fit.nonlinear[c];
      for (const auto& quantity : fit.effect->physicalQuantities(fit.shared, fit.sharedCovariance)) {
        effect[quantity.name] = quantityJson(quantity);
      }
      channel[fit.effect->id()] = effect;
    }
    result[model.channelNames[c]] = channel;
  }
  return result;
}

nlohmann::json toJson(const Comparison& comparison, const FittedModel& model, const Dataset& data) {
  nlohmann::json result = toJson(comparison.data);
  if (comparison.validation) result["validation"] = toJson(*comparison.validation);
  result["failures_analysed_on"] = comparison.failuresOn;
  nlohmann::json windows = nlohmann::json::array();
  for (const auto& w : comparison.worstWindows) {
    windows.push_back({{"start", w.start},
                       {"end", w.end},
                       {"nrmse", w.nrmse},
                       {"worst_channel", w.worstChannel},
                       {"axis", data.timeOrdered() ? "time_s" : "load_Nm"}});
  }
  result["worst_windows"] = windows;
  result["events"] = toJson(comparison.events);
  nlohmann::json regimes = nlohmann::json::object();
  for (const auto& channel : comparison.regimes) {
    nlohmann::json byRegime = nlohmann::json::object();
    for (const auto& regime : channel.regimes) {
      nlohmann::json bins = nlohmann::json::array();
      for (const auto& bin : regime.bins) {
        bins.push_back(
            {{"bin", bin.label}, {"count", bin.count}, {"mean", bin.meanResidual}, {"rms", bin.rmsResidual}});
      }
      byRegime[regime.name] = bins;
    }
    regimes[channel.channel] = byRegime;
  }
  result["regimes"] = regimes;
  nlohmann::json follows = nlohmann::json::array();
  for (const auto& f : comparison.strongestCorrelations) {
    follows.push_back({{"channel", f.channel}, {"signal", f.signal}, {"correlation", f.correlation}});
  }
  result["residual_follows"] = follows;
  result["parameters"] = parametersJson(model);
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& effect : model.spec.effects) effects.push_back(describeEffect(effect));
  result["model"] = {{"kind", toString(model.spec.kind)}, {"effects", effects}};
  nlohmann::json dropped = nlohmann::json::array();
  for (const auto& d : data.quality().dropped) {
    dropped.push_back({{"reason", d.reason}, {"count", d.count}, {"first_lines", d.firstLines}});
  }
  std::vector<std::string> notes = data.quality().notes;
  notes.insert(notes.end(), data.notes().begin(), data.notes().end());
  result["data_quality"] = {
      {"rows", data.quality().dataRows}, {"kept", data.quality().keptRows}, {"dropped", dropped}, {"notes", notes}};
  return result;
}

nlohmann::json toJson(const Diagnosis& diagnosis) {
  nlohmann::json ranking = nlohmann::json::array();
  for (const auto& c : diagnosis.ranking) {
    nlohmann::json entry{{"effect", c.effect},
                         {"discovered", c.discovered},
                         {"joints", c.joints},
                         {"heldout_reduction", c.heldoutReduction},
                         {"score", c.score},
                         {"suggested", c.suggested},
                         {"explanation", c.explanation},
                         {"channel_reduction", c.channelReduction}};
    if (!c.nonlinearName.empty()) {
      nlohmann::json values = nlohmann::json::array();
      for (double v : c.nonlinear) values.push_back(std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v));
      entry[c.nonlinearName] = values;
    }
    if (c.discovered) entry["model_entry"] = c.modelEntry;
    for (const auto& quantity : c.quantities) entry[quantity.name] = quantityJson(quantity);
    ranking.push_back(entry);
  }
  nlohmann::json follows = nlohmann::json::array();
  for (const auto& f : diagnosis.residualFollows) {
    follows.push_back({{"channel", f.channel}, {"signal", f.signal}, {"correlation", f.correlation}});
  }
  auto number = [](double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); };
  nlohmann::json noise = nlohmann::json::array();
  for (double v : diagnosis.noiseFloor) noise.push_back(number(v));
  return {
      {"heldout", diagnosis.heldout},
      {"heldout_base", toJson(diagnosis.heldoutBase)},
      {"noise_floor", noise},
      {"explainable", number(diagnosis.explainable)},
      {"catalogue_explains", diagnosis.catalogueExplains},
      {"ranking", ranking},
      {"skipped", diagnosis.skipped},
      {"residual_follows", follows},
      {"events_left_out", {{"data", toJson(diagnosis.dataEvents)}, {"validation", toJson(diagnosis.validationEvents)}}},
      {"summary", diagnosis.summary}};
}

nlohmann::json toJson(const FitStep& step) {
  nlohmann::json before{{"train", rmseOnly(step.beforeData)}}, after{{"train", rmseOnly(step.afterData)}};
  if (step.beforeValidation) before["validation"] = rmseOnly(*step.beforeValidation);
  if (step.afterValidation) after["validation"] = rmseOnly(*step.afterValidation);
  return {{"added", step.added},
          {"before", before},
          {"after", after},
          {"parameters", parametersJson(step.after)},
          {"events_left_out", {{"data", toJson(step.dataEvents)}, {"validation", toJson(step.validationEvents)}}}};
}

nlohmann::json toJson(const std::vector<SessionStep>& history) {
  nlohmann::json steps = nlohmann::json::array();
  for (std::size_t i = 0; i < history.size(); ++i) {
    const auto& step = history[i];
    nlohmann::json entry{
        {"step", i + 1}, {"command", step.command}, {"effects", step.effects}, {"train", toJson(step.data)}};
    if (step.validation) entry["validation"] = toJson(*step.validation);
    steps.push_back(entry);
  }
  return {{"steps", steps}};
}

SessionStep sessionStepFromJson(const nlohmann::json& json) {
  SessionStep step;
  step.command = json.at("command").get<std::string>();
  step.effects = json.at("effects").get<std::vector<std::string>>();
  step.data = summaryFromJson(json.at("train"));
  if (json.contains("validation")) step.validation = summaryFromJson(json.at("validation"));
  return step;
}

std::string formatDataQuality(const Dataset& data) {
  std::ostringstream text;
  text << data.source() << ": " << data.quality().summary() << "\n";
  for (const auto& note : data.quality().notes) text << "  " << note << "\n";
  for (const auto& note : data.notes()) text << "  " << note << "\n";
  return text.str();
}

std::string formatErrors(const ErrorSummary& data, const ErrorSummary* validation) {
  std::ostringstream text;
  text << padded("channel", 26) << padded("RMSE", 12) << padded("NRMSE", 9) << padded("R2", 9);
  if (validation) text << padded("val RMSE", 12) << padded("val NRMSE", 10) << "val R2";
  text << "\n";
  for (std::size_t c = 0; c < data.channels.size(); ++c) {
    const auto& e = data.channels[c];
    text << padded(e.channel, 26) << padded(format("%.4g", e.rmse), 12) << padded(format("%.4f", e.nrmse), 9)
         << padded(format("%.4f", e.r2), 9);
    if (validation) {
      const auto& v = validation->channels[c];
      text << padded(format("%.4g", v.rmse), 12) << padded(format("%.4f", v.nrmse), 10) << format("%.4f", v.r2);
    }
    text << "\n";
  }
  text << padded("overall NRMSE", 26) << padded("", 12) << padded(format("%.4f", data.overallNrmse), 18);
  if (validation) text << padded("", 12) << format("%.4f", validation->overallNrmse);
  text << "\n";
  return text.str();
}

std::string formatParameters(const FittedModel& model) {
  std::ostringstream text;
  text << "parameters (value ± standard error):\n";
  for (const auto& fit : model.effects) {
    const auto names = fit.effect->parameterNames();
    const auto nonlinear = fit.effect->nonlinearParameter();
    for (int c = 0; c < model.channelCount(); ++c) {
      if (!fit.applied[c]) continue;
      text << "  " << padded(fit.effect->id(), 22) << padded(model.channelNames[c], 26);
      for (std::size_t p = 0; p < names.size(); ++p) {
        const double error = fit.standardErrors[c][static_cast<Eigen::Index>(p)];
        text << names[p] << " = " << format("%.5g", fit.values[c][static_cast<Eigen::Index>(p)])
             << (std::isnan(error) ? std::string(" (not identifiable)") : " ± " + format("%.2g", error)) << "  ";
      }
      if (nonlinear) text << nonlinear->name << " = " << format("%.5g", fit.nonlinear[c]) << " " << nonlinear->unit;
      text << "\n";
    }
    for (const auto& quantity : fit.effect->physicalQuantities(fit.shared, fit.sharedCovariance)) {
      text << "  " << padded(fit.effect->id(), 22) << padded("(all joints)", 26) << quantityText(quantity) << "\n";
    }
  }
  return text.str();
}

std::string formatComparison(const Comparison& comparison) {
  std::ostringstream text;
  text << formatErrors(comparison.data, comparison.validation ? &*comparison.validation : nullptr);
  text << "\nworst windows (" << comparison.failuresOn << "):\n";
  for (const auto& w : comparison.worstWindows) {
    text << "  " << format("%.3f", w.start) << " .. " << format("%.3f", w.end) << "  NRMSE " << format("%.3f", w.nrmse)
         << "  worst " << w.worstChannel << "\n";
  }
  text << "\nevents (" << comparison.failuresOn << "): " << (comparison.events.empty() ? "" : "\n")
       << formatEvents(comparison.events);
  text << "\nresidual by regime (" << comparison.failuresOn << "; mean / rms):\n";
  for (const auto& channel : comparison.regimes) {
    text << "  " << channel.channel << "\n";
    for (const auto& regime : channel.regimes) {
      text << "    " << padded(regime.name, 13);
      for (const auto& bin : regime.bins) {
        text << "[" << bin.label << ": " << format("%.3g", bin.meanResidual) << " / " << format("%.3g", bin.rmsResidual)
             << "] ";
      }
      text << "\n";
    }
  }
  if (!comparison.strongestCorrelations.empty()) {
    text << "\nthe residual follows:";
    for (std::size_t k = 0; k < comparison.strongestCorrelations.size() && k < 6; ++k) {
      const auto& f = comparison.strongestCorrelations[k];
      text << (k ? "," : "") << " " << f.signal << " on " << f.channel << " (r = " << format("%.2f", f.correlation)
           << ")";
    }
    text << "\n";
  }
  return text.str();
}

std::string formatDiagnosis(const Diagnosis& diagnosis) {
  std::ostringstream text;
  text << "held-out data: " << diagnosis.heldout << "; held-out NRMSE of the model as it is "
       << format("%.4f", diagnosis.heldoutBase.overallNrmse) << "\n\n";
  text << padded("rank", 6) << padded("effect", 22) << padded("held-out", 10) << padded("score", 12) << "joints\n";
  for (std::size_t k = 0; k < diagnosis.ranking.size(); ++k) {
    const auto& c = diagnosis.ranking[k];
    std::string joints;
    for (int j : c.joints) joints += (joints.empty() ? "" : ",") + std::to_string(j);
    text << padded(c.suggested ? std::to_string(k + 1) : "-", 6) << padded(c.effect, 22)
         << padded(format("%+.1f%%", -100.0 * c.heldoutReduction), 10) << padded(format("%.4g", c.score), 12)
         << (c.suggested ? joints : std::string("(not significant)")) << "\n";
  }
  for (const auto& c : diagnosis.ranking) {
    if (c.discovered) text << "  " << c.effect << " (a term outside the catalogue): " << c.modelEntry << "\n";
  }
  for (const auto& s : diagnosis.skipped) text << "  not tested: " << s << "\n";
  text << "\n" << diagnosis.summary << "\n";
  return text.str();
}

std::string formatFitStep(const FitStep& step) {
  std::ostringstream text;
  text << "added:";
  for (const auto& a : step.added) text << " " << a;
  if (!step.dataEvents.empty() || !step.validationEvents.empty()) {
    text << "\nleft out as moments, not effects (as diagnose does): " << step.dataEvents.size()
         << " events in the data, " << step.validationEvents.size() << " in the validation data";
  }
  text << "\n" << padded("channel", 26) << padded("train before", 14) << padded("train after", 14);
  if (step.beforeValidation) text << padded("val before", 14) << "val after";
  text << "   (RMSE)\n";
  for (std::size_t c = 0; c < step.beforeData.channels.size(); ++c) {
    text << padded(step.beforeData.channels[c].channel, 26)
         << padded(format("%.4g", step.beforeData.channels[c].rmse), 14)
         << padded(format("%.4g", step.afterData.channels[c].rmse), 14);
    if (step.beforeValidation) {
      text << padded(format("%.4g", step.beforeValidation->channels[c].rmse), 14)
           << format("%.4g", step.afterValidation->channels[c].rmse);
    }
    text << "\n";
  }
  text << padded("overall NRMSE", 26) << padded(format("%.4f", step.beforeData.overallNrmse), 14)
       << padded(format("%.4f", step.afterData.overallNrmse), 14);
  if (step.beforeValidation) {
    text << padded(format("%.4f", step.beforeValidation->overallNrmse), 14)
         << format("%.4f", step.afterValidation->overallNrmse);
  }
  text << "\n\n" << formatParameters(step.after);
  return text.str();
}

std::string formatHistory(const std::vector<SessionStep>& history) {
  std::ostringstream text;
  if (history.empty()) return "no steps recorded yet (run compare or fit with --out DIR)\n";
  text << padded("step", 6) << padded("command", 34) << padded("train NRMSE", 13) << "validation NRMSE\n";
  for (std::size_t i = 0; i < history.size(); ++i) {
    const auto& step = history[i];
    text << padded(std::to_string(i + 1), 6) << padded(step.command, 34)
         << padded(format("%.4f", step.data.overallNrmse), 13)
         << (step.validation ? format("%.4f", step.validation->overallNrmse) : std::string("-")) << "\n";
  }
  const auto& last = history.back();
  const auto& summary = last.validation ? *last.validation : last.data;
  text << "\nRMSE per channel after each step (" << (last.validation ? "validation" : "train") << "):\n"
       << padded("step", 6);
  for (const auto& c : summary.channels) text << padded(c.channel, 20);
  text << "\n";
  for (std::size_t i = 0; i < history.size(); ++i) {
    const auto& s = history[i].validation ? *history[i].validation : history[i].data;
    text << padded(std::to_string(i + 1), 6);
    for (const auto& c : s.channels) text << padded(format("%.4g", c.rmse), 20);
    text << "\n";
  }
  return text.str();
}

}  // namespace arcplan::model
