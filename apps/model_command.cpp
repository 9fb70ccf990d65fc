// arcplan model compare|diagnose|fit|simulate|history — the model-vs-measurement loop (docs/model.md).
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>

#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/model/compare.h"
#include "arcplan/model/diagnose.h"
#include "arcplan/model/plots.h"
#include "arcplan/model/result_formats.h"
#include "arcplan/model/simulate.h"
#include "arcplan/model/workflow.h"
#include "cli_support.h"
#include "commands.h"

namespace arcplan::apps {
namespace {

struct ModelOptions {
  std::vector<std::string> dataRuns, validateRuns;  // compare / diagnose / fit
  std::string model, data, validate, columns, rows, validateRows, out, json, html;
  bool keepParameters = false;
  bool noDiscovery = false;
  bool keepEvents = false;
  std::vector<std::string> add;
  std::string save;
  int folds = 5;
  double minimumReduction = 0.01;
  // simulate
  std::string trajectory = "excitation", format = "rtde";
  double duration = 60.0, rate = 500.0, noise = -1.0;  // noise < 0: the model kind's default
  bool noiseGiven = false;
  unsigned seed = 1;
  int harmonics = 5;
};

// Runs a subcommand's step, which returns its JSON document, and writes that to --json afterwards.
void runStep(const ModelOptions& o, const std::function<nlohmann::json()>& step) {
  nlohmann::json document;
  {
    const DropStdout quiet(o.json == "-");
    document = step();
  }
  if (!o.json.empty()) writeJson(o.json, document);
}

// The limits of diagnose's numbers are the library's (diagnose.h); on the command line a wrong one
// is a usage error, found before any log is read.
void checkDiagnoseOptions(const ModelOptions& o) {
  try {
    model::checkFolds(o.folds, "--folds");
    model::checkMinimumReduction(o.minimumReduction, "--min-reduction");
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

void addKeepEvents(CLI::App& command, ModelOptions& o) {
  command.add_flag("--keep-events", o.keepEvents,
                   "score on every sample: do not leave out the events (moments the residual leaves its noise band "
                   "and comes back, e.g. a push)");
}

void addKeepParameters(CLI::App& command, ModelOptions& o, const std::string& what) {
  command.add_flag("--keep-parameters", o.keepParameters,
                   "use the parameters stored in the model file (a saved fit) instead of refitting; " + what);
}

// The report shows the session kept in --out, so --html needs it.
void addHtmlOption(CLI::App& command, ModelOptions& o, CLI::Option* out) {
  command
      .add_option("--html", o.html, "also write the session's self-contained HTML report (of --out DIR) to this file")
      ->needs(out);
}

// The session report once the step's files are in --out (docs/report.md).
void writeSessionReport(const ModelOptions& o) {
  if (!o.html.empty()) writeHtmlReport(o.out, o.html);
}

void addDataOptions(CLI::App& command, ModelOptions& o) {
  command.add_option("--model", o.model, "model file (YAML: kind, load_torque, effects)")->required();
  command
      .add_option("--data", o.dataRuns,
                  "measured log: RTDE CSV, headerless log with --columns, a run folder of one log_<signal>.csv per "
                  "signal, or force-transfer CSV; several runs of one robot are joined end to end")
      ->required();
  command.add_option("--validate", o.validateRuns,
                     "held-out log(s) (files or run folders, joined like --data): validation errors, events and the "
                     "diagnosis score on it");
  command.add_option("--columns", o.columns,
                     "column map for headerless logs: a preset (ur10e_real) or 'timestamp=1, actual_q=2-7, ...' "
                     "(1-based columns)");
  command.add_option("--rows", o.rows,
                     "use only these 1-based file lines of --data (of every run; a run folder: of every file), e.g. "
                     "355-5090");
  command.add_option("--validate-rows", o.validateRows, "use only these 1-based file lines of --validate");
  auto* out =
      command.add_option("--out", o.out, "directory for PNG plots, their data, and the session history (session.json)");
  command.add_option("--json", o.json, "write the result as JSON to this file ('-' for stdout)");
  addHtmlOption(command, o, out);
}

model::DataFiles dataFiles(const ModelOptions& o) {
  model::DataFiles files;
  files.data = o.dataRuns.front();
  files.moreData.assign(o.dataRuns.begin() + 1, o.dataRuns.end());
  if (!o.validateRuns.empty()) {
    files.validation = o.validateRuns.front();
    files.moreValidation.assign(o.validateRuns.begin() + 1, o.validateRuns.end());
  }
  if (!o.columns.empty())
    files.dataOptions.columns = files.validationOptions.columns = model::parseColumnMap(o.columns);
  if (!o.rows.empty())
    std::tie(files.dataOptions.firstLine, files.dataOptions.lastLine) = model::parseLineRange(o.rows, "--rows");
  if (!o.validateRows.empty()) {
    std::tie(files.validationOptions.firstLine, files.validationOptions.lastLine) =
        model::parseLineRange(o.validateRows, "--validate-rows");
  }
  return files;
}

void printQuality(const model::LoadedData& loaded) {
  std::cout << model::formatDataQuality(loaded.data);
  if (loaded.validation) std::cout << model::formatDataQuality(*loaded.validation);
  std::cout << "\n";
}

void reportPlot(const PlotOutcome& outcome, const std::filesystem::path& directory) {
  if (outcome.ok) {
    std::cout << "plots written to " << directory.string() << "\n";
  } else {
    std::cout << "plots skipped: " << outcome.message << "\n";
  }
}

nlohmann::json runCompare(const ModelOptions& o) {
  const auto spec = model::loadModelFile(o.model);
  const auto loaded = model::loadData(spec, dataFiles(o));
  printQuality(loaded);
  const auto fitted = model::comparedModel(spec, loaded.data, o.keepParameters);
  const auto comparison = model::compareModel(fitted, loaded.data, loaded.validationOrNull());
  std::cout << model::formatComparison(comparison) << "\n" << model::formatParameters(fitted);
  if (!o.out.empty()) {
    const std::filesystem::path directory = o.out;
    auto outcome = model::plotComparison(fitted, loaded.data, directory, "compare_data");
    if (outcome.ok && loaded.validation) {
      outcome = model::plotComparison(fitted, *loaded.validation, directory, "compare_validation");
    }
    reportPlot(outcome, directory);
    model::appendSessionStep(directory / "session.json", model::comparisonStep(spec, comparison));
    writeJson(directory / "compare.json",
              model::toJson(comparison, fitted, loaded.data));  // worst windows for the report
  }
  writeSessionReport(o);
  return model::toJson(comparison, fitted, loaded.data);
}

nlohmann::json runDiagnose(const ModelOptions& o) {
  checkDiagnoseOptions(o);
  const auto spec = model::loadModelFile(o.model);
  const auto loaded = model::loadData(spec, dataFiles(o));
  printQuality(loaded);
  model::DiagnoseOptions options;
  options.folds = o.folds;
  options.minimumReduction = o.minimumReduction;
  options.keepParameters = o.keepParameters;
  options.discover = !o.noDiscovery;
  options.leaveOutEvents = !o.keepEvents;
  const auto diagnosis = model::diagnose(spec, loaded.data, loaded.validationOrNull(), options);
  std::cout << model::formatDiagnosis(diagnosis);
  if (!o.out.empty()) reportPlot(model::plotDiagnosis(diagnosis, o.out), o.out);
  writeSessionReport(o);
  return model::toJson(diagnosis);
}

nlohmann::json runFit(const ModelOptions& o) {
  const auto spec = model::loadModelFile(o.model);
  std::vector<model::EffectSpec> additions;
  for (const auto& text : o.add) additions.push_back(model::parseEffectArgument(text));
  const auto loaded = model::loadData(spec, dataFiles(o));
  printQuality(loaded);
  const auto step =
      model::addEffectsAndFit(spec, additions, loaded.data, loaded.validationOrNull(), o.keepParameters, !o.keepEvents);
  std::cout << model::formatFitStep(step);
  if (!o.save.empty()) {
    model::saveModelFile(model::specWithParameters(step.after), o.save);
    std::cout << "saved the refitted model to " << o.save << "\n";
  }
  if (!o.out.empty()) {
    const std::filesystem::path directory = o.out;
    auto outcome = model::plotFitStep(step, directory);
    if (outcome.ok) outcome = model::plotComparison(step.after, loaded.data, directory, "fit_data");
    if (outcome.ok && loaded.validation)
      outcome = model::plotComparison(step.after, *loaded.validation, directory, "fit_validation");
    reportPlot(outcome, directory);
    model::appendSessionStep(directory / "session.json", model::fitSessionStep(step));
  }
  writeSessionReport(o);
  return model::toJson(step);
}

nlohmann::json runHistory(const ModelOptions& o) {
  if (o.out.empty()) throw UsageError("history: give the session directory with --out DIR");
  const std::filesystem::path directory = o.out;
  const auto session = directory / "session.json";
  if (!std::filesystem::exists(session)) {
    throw Error("history: " + session.string() + " does not exist (run compare or fit with --out " + o.out + " first)");
  }
  const auto history = model::readSession(session);
  std::cout << model::formatHistory(history);
  if (!history.empty()) reportPlot(model::plotHistory(session, directory), directory);
  writeSessionReport(o);
  return model::toJson(history);
}

nlohmann::json runSimulate(const ModelOptions& o) {
  if (o.format != "rtde" && o.format != "record") {
    throw UsageError("--format: expected rtde or record, got '" + o.format + "'");
  }
  requirePositive(o.rate, "--rate", "Hz");
  requirePositive(o.duration, "--duration", "s");
  if (o.harmonics < 1) throw UsageError("--harmonics must be an integer >= 1, got " + std::to_string(o.harmonics));
  if (o.noiseGiven && !(o.noise >= 0.0 && std::isfinite(o.noise))) {
    throw UsageError("--noise must be a standard deviation >= 0, got " + formatNumber(o.noise, 6));
  }
  const auto truth = model::loadModelFile(o.model);
  const auto robot = model::modelRobot(truth);
  auto trajectoryFor = [&](unsigned seed) {
    if (o.trajectory == "excitation") {
      model::ExcitationOptions excitation;
      excitation.duration = o.duration;
      excitation.rate = o.rate;
      excitation.harmonics = o.harmonics;
      excitation.seed = seed;
      Eigen::VectorXd center = Eigen::VectorXd::Zero(robot->dof());
      if (robot->dof() == 6) center << 0.0, -M_PI / 2, M_PI / 4, -M_PI / 2, -M_PI / 2, 0.0;
      return model::excitationTrajectory(center, excitation);
    }
    return model::readTrajectory(o.trajectory, o.rate, truth.derivativeCutoffHz);
  };
  const auto style = o.format == "rtde" ? model::CsvStyle::UrRtde : model::CsvStyle::RecordPy;
  nlohmann::json result{{"model", o.model}, {"kind", model::toString(truth.kind)}, {"logs", nlohmann::json::array()}};
  std::vector<std::pair<std::string, unsigned>> outputs{{o.data, o.seed}};
  if (!o.validate.empty()) outputs.push_back({o.validate, o.seed + 1000});
  // Both logs are simulated before either is written, so a failure leaves no file behind.
  std::vector<model::Log> logs;
  for (const auto& [file, seed] : outputs) {
    model::SimulationOptions simulation;
    simulation.noise = o.noise;
    simulation.seed = seed;
    logs.push_back(model::simulateLog(truth, trajectoryFor(seed), simulation));
  }
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    model::writeLog(logs[i], outputs[i].first, style);
    std::cout << "wrote " << outputs[i].first << ": " << logs[i].rows() << " samples x " << logs[i].jointCount()
              << " joints, seed " << outputs[i].second << "\n";
    result["logs"].push_back({{"file", outputs[i].first}, {"samples", logs[i].rows()}, {"seed", outputs[i].second}});
  }
  return result;
}

}  // namespace

void registerModelCommand(CLI::App& app) {
  auto* modelCommand = app.add_subcommand(
      "model", "compare a robot model with measured logs, diagnose the missing effect, add it, refit");
  modelCommand->require_subcommand(1);
  auto o = std::make_shared<ModelOptions>();

  auto* compare = modelCommand->add_subcommand(
      "compare",
      "fit the model to --data and report RMSE, NRMSE, R² per channel (and on --validate), the worst time "
      "windows, events (moments the residual leaves its noise band, e.g. a push) and the residual by regime");
  addDataOptions(*compare, *o);
  addKeepParameters(*compare, *o, "compare them with the data as they are");
  compare->callback([o] { runStep(*o, [o] { return runCompare(*o); }); });

  auto* diagnose = modelCommand->add_subcommand(
      "diagnose",
      "fit every catalogue effect missing from the model, and terms from every joint's signals, to the "
      "residual, score them on held-out data (--validate, else time-blocked cross-validation) and rank "
      "the explanations");
  addDataOptions(*diagnose, *o);
  diagnose->add_option("--folds", o->folds, "cross-validation folds without --validate")->capture_default_str();
  diagnose
      ->add_option("--min-reduction", o->minimumReduction,
                   "smallest fraction of a channel's held-out residual RMS an effect must remove")
      ->capture_default_str();
  addKeepParameters(*diagnose, *o, "every candidate is fitted to what the kept model leaves");
  diagnose->add_flag("--no-discovery", o->noDiscovery,
                     "try only registered effects, not the library of terms from every joint's signals");
  addKeepEvents(*diagnose, *o);
  diagnose->callback([o] { runStep(*o, [o] { return runDiagnose(*o); }); });

  auto* fit = modelCommand->add_subcommand(
      "fit", "add effects to the model, refit, and report the errors before and after on --data and --validate");
  addDataOptions(*fit, *o);
  fit->add_option("--add", o->add, "effect to add, optionally on some joints: load_friction:1,2 (repeatable)")
      ->required();
  fit->add_option("--save", o->save, "write the refitted model (with parameters and standard errors) to this file");
  addKeepParameters(*fit, *o, "only the added effects are fitted");
  addKeepEvents(*fit, *o);
  fit->callback([o] { runStep(*o, [o] { return runFit(*o); }); });

  auto* history = modelCommand->add_subcommand(
      "history", "the error after every compare/fit step of a session (--out DIR) as a table and a falling-error plot");
  auto* historyOut = history->add_option("--out", o->out, "session directory used with compare/fit --out")->required();
  history->add_option("--json", o->json, "write the history as JSON to this file ('-' for stdout)");
  addHtmlOption(*history, *o, historyOut);
  history->callback([o] { runStep(*o, [o] { return runHistory(*o); }); });

  auto* simulate = modelCommand->add_subcommand(
      "simulate",
      "write synthetic UR10e logs: an excitation (or given) trajectory, the controller's target_moment, and "
      "currents or positions from the model file's effects (its parameters, else typical UR10e values) "
      "plus noise");
  simulate->add_option("--model", o->model, "the true model: kind, effects and optional parameters")->required();
  simulate->add_option("--data", o->data, "log file to write")->required();
  simulate->add_option("--validate", o->validate, "also write a second log (another trajectory and noise seed)");
  simulate
      ->add_option("--trajectory", o->trajectory,
                   "'excitation' (Fourier series) or a CSV with t and q0..q5 (e.g. a planned and scaled path)")
      ->capture_default_str();
  simulate->add_option("--duration", o->duration, "excitation length [s]")->capture_default_str();
  simulate->add_option("--rate", o->rate, "sampling rate [Hz]")->capture_default_str();
  simulate->add_option("--harmonics", o->harmonics, "harmonics of the excitation")->capture_default_str();
  simulate->add_option("--seed", o->seed, "random seed of the trajectory and the noise")->capture_default_str();
  simulate->add_option_function<double>(
      "--noise",
      [o](double noise) {
        o->noise = noise;
        o->noiseGiven = true;
      },
      "noise standard deviation (default 0.05 A for currents, 2e-5 rad for positions)");
  simulate->add_option("--format", o->format, "rtde (ur_rtde, comma-separated) or record (record.py, space-separated)")
      ->capture_default_str();
  simulate->add_option("--json", o->json, "write a summary as JSON to this file ('-' for stdout)");
  simulate->callback([o] { runStep(*o, [o] { return runSimulate(*o); }); });
}

}  // namespace arcplan::apps
