// arcplan.model's result classes: errors, series of measured and predicted values, comparisons, diagnoses, fit steps
// and the error history. Each to_dict() is the JSON the CLI writes for the same result (docs/model.md).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "arcplan/common/error.h"
#include "arcplan/model/result_formats.h"
#include "model_objects.h"

namespace py = pybind11;

namespace arcplan::python {
namespace {

// One log's values per channel: what was measured and what the fitted model predicts.
struct Series {
  std::vector<std::string> channels;
  std::vector<Eigen::VectorXd> time, measured, predicted;
};

Series seriesOf(const FittedOnData& fitted, bool validation) {
  if (validation && !fitted.data->validation) throw Error("series(validation=True): the data has no validation log");
  const auto& data = validation ? *fitted.data->validation : fitted.data->data;
  Series series;
  series.predicted = model::predictAll(fitted.model, data);
  for (int c = 0; c < data.channelCount(); ++c) {
    series.channels.push_back(data.channelName(c));
    series.time.push_back(data.signal("time", c));
    series.measured.push_back(data.measured(c));
  }
  return series;
}

// Channels of one length (joint logs) as one (samples, channels) array; otherwise (gearbox data: points per
// gearbox and direction) a list of one array per channel.
py::object stacked(const std::vector<Eigen::VectorXd>& columns) {
  const bool sameLength = std::all_of(columns.begin(), columns.end(),
                                      [&](const Eigen::VectorXd& c) { return c.size() == columns.front().size(); });
  if (columns.empty() || !sameLength) return py::cast(columns);
  Eigen::MatrixXd matrix(columns.front().size(), static_cast<Eigen::Index>(columns.size()));
  for (std::size_t c = 0; c < columns.size(); ++c) matrix.col(static_cast<Eigen::Index>(c)) = columns[c];
  return py::cast(matrix);
}

py::object timeOf(const Series& series) {
  const bool sameLength = std::all_of(series.time.begin(), series.time.end(),
                                      [&](const Eigen::VectorXd& t) { return t.size() == series.time.front().size(); });
  return sameLength ? py::cast(series.time.front()) : py::cast(series.time);
}

std::vector<Eigen::VectorXd> residuals(const Series& series) {
  std::vector<Eigen::VectorXd> result;
  for (std::size_t c = 0; c < series.measured.size(); ++c) result.push_back(series.measured[c] - series.predicted[c]);
  return result;
}

Eigen::VectorXd column(const model::ErrorSummary& summary, double model::ChannelError::*member) {
  Eigen::VectorXd values(static_cast<Eigen::Index>(summary.channels.size()));
  for (std::size_t c = 0; c < summary.channels.size(); ++c)
    values[static_cast<Eigen::Index>(c)] = summary.channels[c].*member;
  return values;
}

void bindErrors(py::module_& m) {
  py::class_<model::ChannelError>(m, "ChannelError", "RMSE, NRMSE (RMSE / std of the measured channel) and R².")
      .def_readonly("channel", &model::ChannelError::channel)
      .def_readonly("rmse", &model::ChannelError::rmse)
      .def_readonly("nrmse", &model::ChannelError::nrmse)
      .def_readonly("r2", &model::ChannelError::r2)
      .def_readonly("samples", &model::ChannelError::samples)
      .def("__repr__", [](const model::ChannelError& e) {
        return "<ChannelError " + e.channel + " rmse=" + std::to_string(e.rmse) + ">";
      });
  py::class_<model::ErrorSummary>(m, "ErrorSummary", "Errors per channel; overall NRMSE = RMS of the channels' NRMSE.")
      .def_readonly("channels", &model::ErrorSummary::channels)
      .def_readonly("overall_nrmse", &model::ErrorSummary::overallNrmse)
      .def_property_readonly("rmse", [](const model::ErrorSummary& s) { return column(s, &model::ChannelError::rmse); })
      .def_property_readonly("nrmse",
                             [](const model::ErrorSummary& s) { return column(s, &model::ChannelError::nrmse); })
      .def_property_readonly("r2", [](const model::ErrorSummary& s) { return column(s, &model::ChannelError::r2); })
      .def("to_dict", [](const model::ErrorSummary& s) { return toPython(model::toJson(s)); })
      .def("__str__", [](const model::ErrorSummary& s) { return model::formatErrors(s, nullptr); });
}

void bindSeries(py::module_& m) {
  py::class_<Series>(m, "Series",
                     "One log's measured and predicted values: time (samples,), measured, predicted and residual "
                     "(measured - predicted) as (samples, channels) float64 arrays (gearbox data: lists per channel).")
      .def_readonly("channels", &Series::channels)
      .def_property_readonly("time", &timeOf)
      .def_property_readonly("measured", [](const Series& s) { return stacked(s.measured); })
      .def_property_readonly("predicted", [](const Series& s) { return stacked(s.predicted); })
      .def_property_readonly("residual", [](const Series& s) { return stacked(residuals(s)); });
  py::class_<FittedOnData, std::shared_ptr<FittedOnData>>(m, "FittedModel", "A model fitted to the loaded data.")
      .def_property_readonly("channels", [](const FittedOnData& f) { return f.model.channelNames; })
      .def_property_readonly(
          "model", [](const FittedOnData& f) { return model::specWithParameters(f.model); },
          "the model with the fitted parameters (Model.save writes it)")
      .def_property_readonly("parameters",
                             [](const FittedOnData& f) { return toPython(model::parametersJson(f.model)); })
      .def(
          "series", [](const FittedOnData& f, bool validation) { return seriesOf(f, validation); },
          py::arg("validation") = false, "measured and predicted values on the fit data (or the validation data)")
      .def("__str__", [](const FittedOnData& f) { return model::formatParameters(f.model); });
}

void bindComparison(py::module_& m) {
  py::class_<model::WorstWindow>(m, "WorstWindow")
      .def_readonly("start", &model::WorstWindow::start)
      .def_readonly("end", &model::WorstWindow::end)
      .def_readonly("nrmse", &model::WorstWindow::nrmse)
      .def_readonly("worst_channel", &model::WorstWindow::worstChannel);
  py::class_<model::Event>(m, "Event", "A moment the residual leaves its noise band and comes back (a push).")
      .def_readonly("start", &model::Event::start)
      .def_readonly("end", &model::Event::end)
      .def_readonly("joints", &model::Event::joints)
      .def_property_readonly("peak",
                             [](const model::Event& e) { return Eigen::VectorXd::Map(e.peak.data(), e.peak.size()); })
      .def_readonly("peak_scales", &model::Event::peakScales)
      .def_readonly("wrench", &model::Event::wrench, "force at the tool (N, base frame), None where the arm is unknown")
      .def_readonly("wrench_fit", &model::Event::wrenchFit);
  py::class_<model::ResidualCorrelation>(m, "ResidualCorrelation")
      .def_readonly("channel", &model::ResidualCorrelation::channel)
      .def_readonly("signal", &model::ResidualCorrelation::signal)
      .def_readonly("correlation", &model::ResidualCorrelation::correlation);
  py::class_<ComparisonResult>(m, "Comparison", "How well the model predicts the data, and where it fails.")
      .def_property_readonly("data", [](const ComparisonResult& r) { return r.comparison.data; })
      .def_property_readonly("validation", [](const ComparisonResult& r) { return r.comparison.validation; })
      .def_property_readonly("overall_nrmse", [](const ComparisonResult& r) { return r.comparison.data.overallNrmse; })
      .def_property_readonly("failures_on", [](const ComparisonResult& r) { return r.comparison.failuresOn; })
      .def_property_readonly("worst_windows", [](const ComparisonResult& r) { return r.comparison.worstWindows; })
      .def_property_readonly("events", [](const ComparisonResult& r) { return r.comparison.events; })
      .def_property_readonly("residual_follows",
                             [](const ComparisonResult& r) { return r.comparison.strongestCorrelations; })
      .def_property_readonly("fitted", [](const ComparisonResult& r) { return r.fitted; })
      .def_property_readonly("series", [](const ComparisonResult& r) { return seriesOf(*r.fitted, false); })
      .def_property_readonly("validation_series",
                             [](const ComparisonResult& r) -> std::optional<Series> {
                               if (!r.fitted->data->validation) return std::nullopt;
                               return seriesOf(*r.fitted, true);
                             })
      .def("to_dict",
           [](const ComparisonResult& r) {
             return toPython(model::toJson(r.comparison, r.fitted->model, r.fitted->data->data));
           })
      .def("__str__", [](const ComparisonResult& r) { return model::formatComparison(r.comparison); });
}

void bindDiagnosis(py::module_& m) {
  py::class_<model::PhysicalQuantity>(m, "PhysicalQuantity")
      .def_readonly("name", &model::PhysicalQuantity::name)
      .def_readonly("meaning", &model::PhysicalQuantity::meaning)
      .def_readonly("values", &model::PhysicalQuantity::values)
      .def_readonly("standard_errors", &model::PhysicalQuantity::standardErrors);
  py::class_<model::EffectCandidate>(m, "Candidate", "An effect (or discovered term) scored on held-out data.")
      .def_readonly("effect", &model::EffectCandidate::effect)
      .def_readonly("discovered", &model::EffectCandidate::discovered)
      .def_readonly("entry", &model::EffectCandidate::entry, "what fit(add=[...]) adds")
      .def_readonly("model_entry", &model::EffectCandidate::modelEntry)
      .def_readonly("joints", &model::EffectCandidate::joints)
      .def_readonly("heldout_reduction", &model::EffectCandidate::heldoutReduction)
      .def_readonly("score", &model::EffectCandidate::score)
      .def_readonly("suggested", &model::EffectCandidate::suggested)
      .def_property_readonly("channel_reduction",
                             [](const model::EffectCandidate& c) {
                               return Eigen::VectorXd::Map(c.channelReduction.data(), c.channelReduction.size());
                             })
      .def_readonly("quantities", &model::EffectCandidate::quantities)
      .def_readonly("explanation", &model::EffectCandidate::explanation)
      .def("__repr__", [](const model::EffectCandidate& c) {
        return "<Candidate " + model::describeEffect(c.entry) + " -" + std::to_string(100.0 * c.heldoutReduction) +
               "% held-out>";
      });
  py::class_<model::Diagnosis>(m, "Diagnosis", "Which missing effect explains the residual, best first.")
      .def_readonly("heldout", &model::Diagnosis::heldout)
      .def_readonly("heldout_base", &model::Diagnosis::heldoutBase)
      .def_readonly("ranking", &model::Diagnosis::ranking)
      .def_readonly("skipped", &model::Diagnosis::skipped)
      .def_readonly("residual_follows", &model::Diagnosis::residualFollows)
      .def_property_readonly(
          "noise_floor",
          [](const model::Diagnosis& d) { return Eigen::VectorXd::Map(d.noiseFloor.data(), d.noiseFloor.size()); })
      .def_readonly("explainable", &model::Diagnosis::explainable)
      .def_readonly("catalogue_explains", &model::Diagnosis::catalogueExplains)
      .def_readonly("summary", &model::Diagnosis::summary)
      .def_readonly("data_events", &model::Diagnosis::dataEvents)
      .def_readonly("validation_events", &model::Diagnosis::validationEvents)
      .def("to_dict", [](const model::Diagnosis& d) { return toPython(model::toJson(d)); })
      .def("__str__", &model::formatDiagnosis);
}

void bindFitStep(py::module_& m) {
  const auto fitted = [](const FitResult& r, const model::FittedModel& model) {
    return std::make_shared<FittedOnData>(FittedOnData{model, r.data});
  };
  py::class_<FitResult>(m, "FitStep", "Effects added and the model refitted: errors before and after.")
      .def_property_readonly("added", [](const FitResult& r) { return r.step.added; })
      .def_property_readonly("before", [](const FitResult& r) { return r.step.beforeData; })
      .def_property_readonly("after", [](const FitResult& r) { return r.step.afterData; })
      .def_property_readonly("before_validation", [](const FitResult& r) { return r.step.beforeValidation; })
      .def_property_readonly("after_validation", [](const FitResult& r) { return r.step.afterValidation; })
      .def_property_readonly("before_fitted", [fitted](const FitResult& r) { return fitted(r, r.step.before); })
      .def_property_readonly("after_fitted", [fitted](const FitResult& r) { return fitted(r, r.step.after); })
      .def_property_readonly(
          "model", [](const FitResult& r) { return model::specWithParameters(r.step.after); },
          "the refitted model with its parameters (what `fit --save` writes)")
      .def("to_dict", [](const FitResult& r) { return toPython(model::toJson(r.step)); })
      .def("__str__", [](const FitResult& r) { return model::formatFitStep(r.step); });
}

void bindHistory(py::module_& m) {
  py::class_<model::SessionStep>(m, "HistoryStep")
      .def_readonly("command", &model::SessionStep::command)
      .def_readonly("effects", &model::SessionStep::effects)
      .def_readonly("data", &model::SessionStep::data)
      .def_readonly("validation", &model::SessionStep::validation);
  const auto overall = [](const History& h, bool validation) {
    Eigen::VectorXd values(static_cast<Eigen::Index>(h.steps.size()));
    for (std::size_t i = 0; i < h.steps.size(); ++i) {
      const auto& step = h.steps[i];
      values[static_cast<Eigen::Index>(i)] = !validation       ? step.data.overallNrmse
                                             : step.validation ? step.validation->overallNrmse
                                                               : std::numeric_limits<double>::quiet_NaN();
    }
    return values;
  };
  py::class_<History>(m, "History", "The error after every step of the loop (compare, fit +effect, ...).")
      .def(py::init<>())
      .def_readonly("steps", &History::steps)
      .def(
          "add",
          [](History& h, const ComparisonResult& r) {
            h.steps.push_back(model::comparisonStep(r.fitted->model.spec, r.comparison));
          },
          py::arg("result"))
      .def(
          "add", [](History& h, const FitResult& r) { h.steps.push_back(model::fitSessionStep(r.step)); },
          py::arg("result"))
      .def_property_readonly("overall_nrmse", [overall](const History& h) { return overall(h, false); })
      .def_property_readonly(
          "validation_overall_nrmse", [overall](const History& h) { return overall(h, true); },
          "per step; NaN where a step had no validation data")
      .def("to_dict", [](const History& h) { return toPython(model::toJson(h.steps)); })
      .def("__len__", [](const History& h) { return h.steps.size(); })
      .def("__str__", [](const History& h) { return model::formatHistory(h.steps); });
}

}  // namespace

void bindModelResults(py::module_& m) {
  bindErrors(m);
  bindSeries(m);
  bindComparison(m);
  bindDiagnosis(m);
  bindFitStep(m);
  bindHistory(m);
}

}  // namespace arcplan::python
