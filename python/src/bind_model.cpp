// arcplan.model: the model-vs-measurement loop from Python (docs/python.md, docs/model.md). Logs from files (RTDE
// CSV, headerless with a column map, run folders) or from NumPy arrays, model files, and compare / diagnose / fit
// with the error history. The same library calls as `arcplan model ...`; the GIL is released while they run.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arcplan/common/error.h"
#include "arcplan/model/measurements.h"
#include "arcplan/model/model_spec.h"
#include "arcplan/model/result_formats.h"
#include "bindings.h"
#include "model_objects.h"

namespace py = pybind11;

namespace arcplan::python {
namespace {

using Path = std::filesystem::path;

model::LogReadOptions readOptions(const std::optional<std::string>& columns, const std::optional<std::string>& rows,
                                  const std::string& rowsOption) {
  model::LogReadOptions options;
  if (columns) options.columns = model::parseColumnMap(*columns);
  if (rows) std::tie(options.firstLine, options.lastLine) = model::parseLineRange(*rows, rowsOption);
  return options;
}

// A NumPy array of one signal as rows x columns; a 1-D array is one column (a scalar signal, or the time).
Eigen::MatrixXd signalMatrix(const std::string& source, const std::string& name, const py::handle& object) {
  const auto array = py::array_t<double, py::array::f_style | py::array::forcecast>::ensure(object);
  if (!array) throw Error(source + ": " + name + ": expected an array of numbers");
  if (array.ndim() != 1 && array.ndim() != 2) {
    throw Error(source + ": " + name + ": expected an array of shape (rows,) or (rows, joints), got " +
                std::to_string(array.ndim()) + " dimensions");
  }
  const Eigen::Index rows = array.shape(0), columns = array.ndim() == 2 ? array.shape(1) : 1;
  return Eigen::Map<const Eigen::MatrixXd>(array.data(), rows, columns);
}

std::shared_ptr<model::Log> logFromArrays(const py::handle& time, const py::dict& signals, const std::string& source) {
  const Eigen::MatrixXd times = signalMatrix(source, "time", time);
  if (times.cols() != 1)
    throw Error(source + ": time: expected one column (rows,), got " + std::to_string(times.cols()));
  std::map<std::string, Eigen::MatrixXd> values;
  for (const auto& [name, array] : signals) {
    const auto key = py::cast<std::string>(name);
    values[key] = signalMatrix(source, key, array);
  }
  return std::make_shared<model::Log>(model::makeLog(source, times.col(0), std::move(values)));
}

// The values of one signal of a log: (rows, joints) for joint signals, (rows,) for scalar ones.
py::object logSignal(const model::Log& log, const std::string& name) {
  const auto scalar = log.scalars.find(name);
  if (scalar != log.scalars.end()) return py::cast(scalar->second);
  return py::cast(log.vector(name));
}

// One item or a list (or tuple) of them.
py::list itemsOf(const py::handle& object) {
  const auto value = py::reinterpret_borrow<py::object>(object);
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) return py::list(value);
  py::list items;
  items.append(value);
  return items;
}

// `data` as given to load_data: one file or Log, or a list of them (runs of one robot, joined end to end).
struct Runs {
  std::vector<Path> files;
  std::vector<model::Log> logs;
};

Runs runsOf(const py::handle& object, const std::string& what) {
  Runs runs;
  if (object.is_none()) return runs;
  const py::list items = itemsOf(object);
  for (const auto& item : items) {
    if (py::isinstance<model::Log>(item)) {
      runs.logs.push_back(py::cast<const model::Log&>(item));
    } else {
      runs.files.push_back(py::cast<Path>(item));
    }
  }
  if (!runs.files.empty() && !runs.logs.empty()) {
    throw py::type_error(what + ": give log files or Log objects, not both");
  }
  return runs;
}

DataPointer loadData(const model::ModelSpec& spec, const py::handle& data, const py::handle& validate,
                     const std::optional<std::string>& columns, const std::optional<std::string>& rows,
                     const std::optional<std::string>& validateRows) {
  const Runs dataRuns = runsOf(data, "data"), validationRuns = runsOf(validate, "validate");
  if (dataRuns.files.empty() && dataRuns.logs.empty()) throw Error("data: give at least one log file or Log");
  const bool fromLogs = !dataRuns.logs.empty();
  if (fromLogs ? !validationRuns.files.empty() : !validationRuns.logs.empty()) {
    throw py::type_error("data and validate: give log files for both or Log objects for both");
  }
  py::gil_scoped_release release;
  if (fromLogs)
    return std::make_shared<model::LoadedData>(model::prepareData(spec, dataRuns.logs, validationRuns.logs));
  model::DataFiles files;
  files.data = dataRuns.files.front();
  files.moreData.assign(dataRuns.files.begin() + 1, dataRuns.files.end());
  if (!validationRuns.files.empty()) {
    files.validation = validationRuns.files.front();
    files.moreValidation.assign(validationRuns.files.begin() + 1, validationRuns.files.end());
  }
  files.dataOptions = readOptions(columns, rows, "rows");
  files.validationOptions = readOptions(columns, validateRows, "validate_rows");
  return std::make_shared<model::LoadedData>(model::loadData(spec, files));
}

// What fit(add=...) accepts: "load_friction:1,2", an Effect, or a diagnosis Candidate; one or a list.
std::vector<model::EffectSpec> additionsOf(const py::handle& object) {
  const py::list items = itemsOf(object);
  std::vector<model::EffectSpec> additions;
  for (const auto& item : items) {
    if (py::isinstance<py::str>(item)) {
      additions.push_back(model::parseEffectArgument(py::cast<std::string>(item)));
    } else if (py::isinstance<model::EffectCandidate>(item)) {
      additions.push_back(py::cast<const model::EffectCandidate&>(item).entry);
    } else if (py::isinstance<model::EffectSpec>(item)) {
      additions.push_back(py::cast<model::EffectSpec>(item));
    } else {
      throw py::type_error("add: expected 'effect[:joints]', an Effect or a Candidate, got " +
                           py::cast<std::string>(py::repr(item)));
    }
  }
  return additions;
}

void bindSpecs(py::module_& m) {
  py::class_<model::EffectSpec>(m, "Effect",
                                "An effect entry of a model file: catalogue id (or expression) and joints.")
      .def_readonly("id", &model::EffectSpec::id)
      .def_readonly("joints", &model::EffectSpec::joints)
      .def_readonly("expressions", &model::EffectSpec::expressions)
      .def_readonly("explanation", &model::EffectSpec::explanation)
      .def("__str__", &model::describeEffect)
      .def("__repr__", [](const model::EffectSpec& e) { return "<Effect " + model::describeEffect(e) + ">"; });
  m.def("parse_effect", &model::parseEffectArgument, py::arg("text"),
        "'coulomb' or 'load_friction:1,2' as on the command line (fit --add)");
  py::class_<model::ModelSpec>(m, "Model", "A model file: kind, load torque, effects (and fitted parameters).")
      .def_readonly("name", &model::ModelSpec::name)
      .def_property_readonly("kind", [](const model::ModelSpec& s) { return model::toString(s.kind); })
      .def_property_readonly("load_torque", [](const model::ModelSpec& s) { return model::toString(s.loadTorque); })
      .def_readonly("effects", &model::ModelSpec::effects)
      .def_property_readonly("source", [](const model::ModelSpec& s) { return s.source.string(); })
      .def("has_effect", &model::ModelSpec::hasEffect, py::arg("id"))
      .def("to_yaml", &model::toYaml)
      .def(
          "save", [](const model::ModelSpec& s, const Path& file) { model::saveModelFile(s, file); }, py::arg("path"))
      .def("__repr__", [](const model::ModelSpec& s) {
        std::string effects;
        for (const auto& e : s.effects) effects += (effects.empty() ? "" : ", ") + model::describeEffect(e);
        return "<Model " + model::toString(s.kind) + " [" + effects + "]>";
      });
  m.def("load_model", &model::loadModelFile, py::arg("path"), "read and check a model file (YAML)");
  m.def("parse_model", &model::parseModelYaml, py::arg("text"), py::arg("source") = Path("model.yaml"),
        "a model file's text; `source` names it in messages");
}

void bindLogs(py::module_& m) {
  py::class_<model::Log, std::shared_ptr<model::Log>>(m, "Log", "A measured log: time and named signals.")
      .def_property_readonly("source", [](const model::Log& l) { return l.source.string(); })
      .def_readonly("time", &model::Log::time)
      .def_property_readonly("rows", &model::Log::rows)
      .def_property_readonly("joint_count", &model::Log::jointCount)
      .def_property_readonly("signals",
                             [](const model::Log& l) {
                               std::vector<std::string> names;
                               for (const auto& [name, values] : l.vectors) names.push_back(name);
                               for (const auto& [name, values] : l.scalars) names.push_back(name);
                               return names;
                             })
      .def("signal", &logSignal, py::arg("name"), "(rows, joints) for joint signals, (rows,) for scalar ones")
      .def("__getitem__", &logSignal, py::arg("name"))
      .def_property_readonly("quality", [](const model::Log& l) { return l.quality.summary(); })
      .def("__repr__", [](const model::Log& l) {
        return "<Log " + l.source.string() + ": " + std::to_string(l.rows()) + " rows>";
      });
  m.def(
      "read_log",
      [](const Path& path, const std::optional<std::string>& columns, const std::optional<std::string>& rows) {
        const auto options = readOptions(columns, rows, "rows");
        py::gil_scoped_release release;
        return std::make_shared<model::Log>(model::readLog(path, options));
      },
      py::arg("path"), py::kw_only(), py::arg("columns") = py::none(), py::arg("rows") = py::none(),
      "an RTDE CSV, a headerless log with `columns` ('ur10e_real' or 'timestamp=1, actual_q=2-7, ...'), or a run "
      "folder; `rows` keeps 1-based file lines ('355-5090')");
  m.def("log_from_arrays", &logFromArrays, py::arg("time"), py::arg("signals"), py::arg("source") = "arrays",
        "a log from NumPy arrays: time (rows,) in s, increasing; signals {RTDE name: (rows, joints) or (rows,)}");
}

void bindData(py::module_& m) {
  py::class_<model::LoadedData, DataPointer>(m, "Data", "Logs prepared for a model: the fit data and validation data.")
      .def_property_readonly("channels",
                             [](const model::LoadedData& d) {
                               std::vector<std::string> names;
                               for (int c = 0; c < d.data.channelCount(); ++c) names.push_back(d.data.channelName(c));
                               return names;
                             })
      .def_property_readonly("samples", [](const model::LoadedData& d) { return d.data.samples(0); })
      .def_property_readonly("validation_samples",
                             [](const model::LoadedData& d) -> std::optional<Eigen::Index> {
                               if (!d.validation) return std::nullopt;
                               return d.validation->samples(0);
                             })
      .def_property_readonly("quality", [](const model::LoadedData& d) {
        return model::formatDataQuality(d.data) + (d.validation ? model::formatDataQuality(*d.validation) : "");
      });
  m.def("load_data", &loadData, py::arg("model"), py::arg("data"), py::arg("validate") = py::none(), py::kw_only(),
        py::arg("columns") = py::none(), py::arg("rows") = py::none(), py::arg("validate_rows") = py::none(),
        "the logs a model is compared with: files or run folders (`columns`, `rows`, `validate_rows` as on the "
        "command line) or Log objects; a list is several runs of one robot");
}

void bindLoop(py::module_& m) {
  m.def(
      "compare",
      [](const model::ModelSpec& spec, const DataPointer& data, bool keepParameters,
         const std::optional<Path>& session) {
        py::gil_scoped_release release;
        model::checkPreparedFor(*data, spec);
        auto fitted =
            std::make_shared<FittedOnData>(FittedOnData{model::comparedModel(spec, data->data, keepParameters), data});
        ComparisonResult result{model::compareModel(fitted->model, data->data, data->validationOrNull()), fitted};
        if (session)
          model::appendSessionStep(*session / "session.json", model::comparisonStep(spec, result.comparison));
        return result;
      },
      py::arg("model"), py::arg("data").none(false), py::kw_only(), py::arg("keep_parameters") = false,
      py::arg("session") = py::none(),
      "fit the model to the data (or keep its parameters) and compare; `session`: a folder whose session.json gets "
      "the step, as `compare --out`");
  m.def(
      "diagnose",
      [](const model::ModelSpec& spec, const DataPointer& data, int folds, double minimumReduction, bool keepParameters,
         bool discovery, bool keepEvents, const std::vector<std::string>& candidates) {
        model::DiagnoseOptions options;
        options.folds = folds;
        options.minimumReduction = minimumReduction;
        options.keepParameters = keepParameters;
        options.discover = discovery;
        options.leaveOutEvents = !keepEvents;
        options.candidates = candidates;
        py::gil_scoped_release release;
        model::checkPreparedFor(*data, spec);
        return model::diagnose(spec, data->data, data->validationOrNull(), options);
      },
      py::arg("model"), py::arg("data").none(false), py::kw_only(), py::arg("folds") = 5,
      py::arg("min_reduction") = 0.01, py::arg("keep_parameters") = false, py::arg("discovery") = true,
      py::arg("keep_events") = false, py::arg("candidates") = std::vector<std::string>{},
      "rank the missing effects by the held-out residual they remove (as `arcplan model diagnose`)");
  m.def(
      "fit",
      [](const model::ModelSpec& spec, const DataPointer& data, const py::object& add, bool keepParameters,
         const std::optional<Path>& session) {
        const auto additions = additionsOf(add);
        py::gil_scoped_release release;
        model::checkPreparedFor(*data, spec);
        FitResult result{model::addEffectsAndFit(spec, additions, data->data, data->validationOrNull(), keepParameters),
                         data};
        if (session) model::appendSessionStep(*session / "session.json", model::fitSessionStep(result.step));
        return result;
      },
      py::arg("model"), py::arg("data").none(false), py::arg("add"), py::kw_only(), py::arg("keep_parameters") = false,
      py::arg("session") = py::none(),
      "add effects ('load_friction:1,2', an Effect or a diagnosis Candidate), refit, errors before and after");
  m.def(
      "read_history", [](const Path& session) { return History{model::readSession(session / "session.json")}; },
      py::arg("session"), "the steps recorded in a session folder's session.json (empty when there is none)");
}

}  // namespace

void bindModel(py::module_& parent) {
  auto m = parent.def_submodule("model", "compare a robot model with measured logs, diagnose, fit, history");
  bindSpecs(m);
  bindLogs(m);
  bindData(m);
  bindModelResults(m);
  bindLoop(m);
}

}  // namespace arcplan::python
