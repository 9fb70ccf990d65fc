#include "arcplan/report/model_session_report.h"


#include "arcplan/common/error.h"
#include "arcplan/model/report.h"
#include "arcplan/model/workflow.h"
#include "arcplan/report/model_series.h"
#include "json_file.h"

namespace arcplan::report {
namespace {

// Of "fit_<which>_series.csv" and "compare_<which>_series.csv" the newer one: the latest step.
std::filesystem::path latestSeries(const std::filesystem::path& session, const std::string& which) {
  std::filesystem::path latest;
  for (const char* step : {"compare", "fit"}) {
    const auto file = session / (std::string(step) + "_" + which + "_series.csv");
    if (!std::filesystem::exists(file)) continue;
    if (latest.empty() || std::filesystem::last_write_time(file) >= std::filesystem::last_write_time(latest)) latest = file;
  }
  return latest;
}

nlohmann::json seriesJson(const std::filesystem::path& file, std::size_t maxSamples) {
  nlohmann::json channels = nlohmann::json::array();
  for (const auto& series : readModelSeries(file, maxSamples)) {
    channels.push_back({{"channel", series.channel},
                        {"time", series.time},
                        {"measured", series.measured},
                        {"predicted", series.predicted},
                        {"signals", series.signals}});
  }
  return {{"file", file.filename().string()}, {"channels", channels}};
}

std::string joinedJoints(const nlohmann::json& joints) {
  std::string text;
  for (const auto& joint : joints) text += (text.empty() ? "" : ",") + std::to_string(joint.get<int>());
  return text;
}

// What to write to add the suggested effects: the `--add` option and the model file's effects line
// (model_spec.h syntax "effect:joints"), after the effects the session's last step had.
nlohmann::json suggestedModelLines(const nlohmann::json& diagnosis, const std::vector<model::SessionStep>& history) {
  std::vector<std::string> additions;
  for (const auto& candidate : diagnosis.value("ranking", nlohmann::json::array())) {
    if (candidate.value("suggested", false)) additions.push_back(candidate.at("effect").get<std::string>() + ":" + joinedJoints(candidate.at("joints")));
  }
  if (additions.empty()) return nullptr;
  std::string effects;
  if (!history.empty()) {
    for (const auto& effect : history.back().effects) effects += (effects.empty() ? "" : ", ") + effect;
  }
  std::string command = "arcplan model fit";
  for (const auto& addition : additions) {
    effects += (effects.empty() ? "" : ", ") + addition;
    command += " --add " + addition;
  }
  return {{"effects_line", "effects: [" + effects + "]"}, {"fit_command", command + " --save next.yaml"}};
}

}  // namespace

nlohmann::json modelSessionReportData(const std::filesystem::path& session, const ModelReportOptions& options) {
  const auto sessionFile = session / "session.json";
  if (!std::filesystem::exists(sessionFile)) {
    throw Error(session.string() + ": not a model session folder (no session.json; run arcplan model compare or fit with --out " +
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
    missing.push_back("No measured-vs-predicted series (compare_data_series.csv or fit_data_series.csv) in " + session.string() +
                      ": run arcplan model compare --out " + session.string() + ".");
  }
  const auto compare = session / "compare.json";
  data["comparison"] = std::filesystem::exists(compare) ? detail::readJsonFile(compare) : nlohmann::json(nullptr);
  if (data["comparison"].is_null()) {
    missing.push_back("No compare.json in " + session.string() + ": the worst windows and regimes come from arcplan model compare --out.");
  }
  const auto diagnose = session / "diagnose_ranking.json";
  data["diagnosis"] = std::filesystem::exists(diagnose) ? detail::readJsonFile(diagnose) : nlohmann::json(nullptr);
  if (data["diagnosis"].is_null()) {
    missing.push_back("No diagnosis in " + session.string() + " (diagnose_ranking.json): run arcplan model diagnose --out " +
                      session.string() + ".");
    data["model_lines"] = nullptr;
  } else {
    data["model_lines"] = suggestedModelLines(data["diagnosis"], history);
  }
  const auto fit = session / "fit_before_after.json";
  data["fit"] = std::filesystem::exists(fit) ? detail::readJsonFile(fit) : nlohmann::json(nullptr);
  return data;
}

}  // namespace arcplan::report
