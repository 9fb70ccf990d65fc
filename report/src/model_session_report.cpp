#include "arcplan/report/model_session_report.h"

#include <algorithm>

#include "arcplan/common/error.h"
#include "arcplan/model/result_formats.h"
#include "arcplan/model/workflow.h"
#include "arcplan/report/model_series.h"
#include "compact_number.h"
#include "json_file.h"

namespace arcplan::report {
namespace {

// Of "fit_<which>_series.csv" and "compare_<which>_series.csv" the newer one: the latest step.
std::filesystem::path latestSeries(const std::filesystem::path& session, const std::string& which) {
  std::filesystem::path latest;
  for (const char* step : {"compare", "fit"}) {
    const auto file = session / (std::string(step) + "_" + which + "_series.csv");
    if (!std::filesystem::exists(file)) continue;
    if (latest.empty() || std::filesystem::last_write_time(file) >= std::filesystem::last_write_time(latest))
      latest = file;
  }
  return latest;
}

nlohmann::json compact(const std::vector<double>& values) {
  nlohmann::json out = nlohmann::json::array();
  for (const double value : values) out.push_back(detail::withSignificantDigits(value, 5));
  return out;
}

nlohmann::json seriesJson(const std::filesystem::path& file, std::size_t maxSamples) {
  nlohmann::json channels = nlohmann::json::array();
  for (const auto& series : readModelSeries(file, maxSamples)) {
    nlohmann::json signals = nlohmann::json::object();
    for (const auto& [signal, values] : series.signals) signals[signal] = compact(values);
    channels.push_back({{"channel", series.channel},
                        {"time", compact(series.time)},
                        {"measured", compact(series.measured)},
                        {"predicted", compact(series.predicted)},
                        {"signals", signals}});
  }
  return {{"file", file.filename().string()}, {"channels", channels}};
}

std::string joinedJoints(const nlohmann::json& joints) {
  std::string text;
  for (const auto& joint : joints) text += (text.empty() ? "" : ",") + std::to_string(joint.get<int>());
  return text;
}

// A suggested candidate as a model-file effect entry: the catalogue's "effect:joints" syntax
// (model_spec.h), or the expression entry the diagnosis wrote for a term it discovered.
std::string modelEntry(const nlohmann::json& candidate) {
  if (candidate.contains("model_entry")) return candidate.at("model_entry").get<std::string>();
  return candidate.at("effect").get<std::string>() + ":" + joinedJoints(candidate.at("joints"));
}

// What to write to add the best suggestion: the model file's effects line after the effects of the
// session's last step, and for a catalogue effect the `fit --add` command; every suggested entry too.
nlohmann::json suggestedModelLines(const nlohmann::json& diagnosis, const std::vector<model::SessionStep>& history) {
  nlohmann::json entries = nlohmann::json::array();
  for (const auto& candidate : diagnosis.value("ranking", nlohmann::json::array())) {
    if (candidate.value("suggested", false)) entries.push_back(modelEntry(candidate));
  }
  if (entries.empty()) return nullptr;
  const auto& best = *std::find_if(diagnosis["ranking"].begin(), diagnosis["ranking"].end(),
                                   [](const nlohmann::json& c) { return c.value("suggested", false); });
  std::string effects;
  if (!history.empty()) {
    for (const auto& effect : history.back().effects) effects += effect + ", ";
  }
  nlohmann::json lines{{"effects_line", "effects: [" + effects + modelEntry(best) + "]"}, {"entries", entries}};
  lines["fit_command"] = best.contains("model_entry")
                             ? nlohmann::json(nullptr)
                             : nlohmann::json("arcplan model fit --add " + modelEntry(best) + " --save next.yaml");
  return lines;
}

}  // namespace

nlohmann::json modelSessionReportData(const std::filesystem::path& session, const ModelReportOptions& options) {
  const auto sessionFile = session / "session.json";
  if (!std::filesystem::exists(sessionFile)) {
    throw Error(session.string() +
                ": not a model session folder (no session.json; run arcplan model compare or fit with --out " +
                session.string() + ")");
  }
  const auto history = model::readSession(sessionFile);
  nlohmann::json data{{"kind", "model"}, {"source", session.string()}, {"missing", nlohmann::json::array()}};
  auto& missing = data["missing"];
  data["history"] = model::toJson(history);
  for (const char* which : {"data", "validation"}) {
    const auto file = latestSeries(session, which);
    data["series"][which] = file.empty() ? nlohmann::json(nullptr) : seriesJson(file, options.maxSamplesPerChannel);
  }
  if (data["series"]["data"].is_null()) {
    missing.push_back("No measured-vs-predicted series (compare_data_series.csv or fit_data_series.csv) in " +
                      session.string() + ": run arcplan model compare --out " + session.string() + ".");
  }
  const auto compare = session / "compare.json";
  data["comparison"] = std::filesystem::exists(compare) ? detail::readJsonFile(compare) : nlohmann::json(nullptr);
  if (data["comparison"].is_null()) {
    missing.push_back("No compare.json in " + session.string() +
                      ": the worst windows and regimes come from arcplan model compare --out.");
  }
  const auto diagnose = session / "diagnose_ranking.json";
  data["diagnosis"] = std::filesystem::exists(diagnose) ? detail::readJsonFile(diagnose) : nlohmann::json(nullptr);
  if (data["diagnosis"].is_null()) {
    missing.push_back("No diagnosis in " + session.string() +
                      " (diagnose_ranking.json): run arcplan model diagnose --out " + session.string() + ".");
    data["model_lines"] = nullptr;
  } else {
    data["model_lines"] = suggestedModelLines(data["diagnosis"], history);
  }
  const auto fit = session / "fit_before_after.json";
  data["fit"] = std::filesystem::exists(fit) ? detail::readJsonFile(fit) : nlohmann::json(nullptr);
  return data;
}

}  // namespace arcplan::report
