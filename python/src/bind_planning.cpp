// Planning: arcplan.plan runs benchmarks::planQuery, the function behind `arcplan plan`, with the GIL
// released; the result has the fields of `plan --json` (the metric names from the metric table) and
// the joint path as an (N, 6) array.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "arcplan/benchmarks/plan_query.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/planners/planner_registry.h"
#include "arcplan/trajectory/metric_descriptors.h"
#include "bindings.h"
#include "errors.h"
#include "json_objects.h"
#include "scene_handle.h"
#include "trajectory_objects.h"

namespace py = pybind11;

namespace arcplan::python {
namespace {

using Planned = benchmarks::PlannedQuery;

// A scene object from load_scene, or a scene file (a path or a name under the data folder).
std::shared_ptr<const collision::Scene> sceneOf(const py::handle& scene) {
  if (py::isinstance<SceneHandle>(scene)) return scene.cast<const SceneHandle&>().scene;
  std::filesystem::path file;
  try {
    file = scene.cast<std::filesystem::path>();
  } catch (const py::cast_error&) {
    throw Error("scene_file: expected a scene file (str or path) or an arcplan.Scene, got " +
                py::str(py::type::of(scene).attr("__name__")).cast<std::string>());
  }
  return std::make_shared<const collision::Scene>(collision::loadScene(resolveDataPath(file)));
}

// Planner parameters as `--param name=value` writes them; True/False as OMPL's 1/0.
std::vector<std::pair<std::string, std::string>> parameterTexts(const py::dict& parameters) {
  std::vector<std::pair<std::string, std::string>> texts;
  for (const auto& [name, value] : parameters) {
    const std::string text =
        py::isinstance<py::bool_>(value) ? (value.cast<bool>() ? "1" : "0") : py::str(value).cast<std::string>();
    texts.emplace_back(py::str(name).cast<std::string>(), text);
  }
  return texts;
}

std::shared_ptr<Planned> plan(const py::handle& scene, const std::optional<std::string>& query,
                              const std::string& planner, const py::dict& parameters,
                              const std::optional<std::uint32_t>& seed, double timeLimit,
                              const std::optional<double>& maxTcpSpeed, double clearance) {
  benchmarks::PlanQueryOptions options;
  options.planner = planner;
  options.parameters = parameterTexts(parameters);
  options.seed = seed;
  options.timeLimit = timeLimit;
  options.maxTcpSpeed = maxTcpSpeed;
  options.clearance = clearance;
  const auto loaded = sceneOf(scene);
  py::gil_scoped_release release;
  return std::make_shared<Planned>(benchmarks::planQuery(loaded, query.value_or(""), options));
}

// A metric of the measured path; None without a path or where it is not defined (NaN: e.g. the
// execution time of an unscaled path).
py::object metricOf(const Planned& planned, double trajectory::TrajectoryMetrics::*member) {
  if (!planned.measurement) return py::none();
  const double value = planned.measurement->metrics.*member;
  return std::isfinite(value) ? py::object(py::float_(value)) : py::none();
}

py::object toDict(const Planned& planned) { return toPython(benchmarks::toJson(planned)); }

}  // namespace

void bindPlanning(py::module_& module) {
  py::class_<Planned, std::shared_ptr<Planned>> result(
      module, "PlanResult", "What arcplan.plan found: the fields of `arcplan plan --json`, the path as (N, 6).");
  result.def_property_readonly("status", [](const Planned& p) { return benchmarks::toString(p.status); })
      .def_property_readonly("reason", [](const Planned& p) { return p.reason; })
      .def_property_readonly("scene", [](const Planned& p) { return p.sceneName; })
      .def_property_readonly("query", [](const Planned& p) { return p.queryName; })
      .def_property_readonly("planner", [](const Planned& p) { return p.options.planner; })
      .def_property_readonly("parameters", [](const Planned& p) { return p.parameterValues; })
      .def_property_readonly("seed", [](const Planned& p) { return p.options.seed; })
      .def_property_readonly("time_limit_s", [](const Planned& p) { return p.options.timeLimit; })
      .def_property_readonly("vmax_mps", [](const Planned& p) { return p.options.maxTcpSpeed; })
      .def_property_readonly("clearance_m", [](const Planned& p) { return p.options.clearance; })
      .def_property_readonly("clearance_kept",
                             [](const Planned& p) -> std::optional<bool> {
                               if (!p.measurement) return std::nullopt;
                               return p.clearanceKept;
                             })
      .def_property_readonly(trajectory::solveTimeDescriptor().key.c_str(),
                             [](const Planned& p) { return p.solveTime; })
      .def_property_readonly(benchmarks::kSimplificationTimeKey, [](const Planned& p) { return p.simplificationTime; })
      .def_property_readonly("mode",
                             [](const Planned& p) -> std::optional<std::string> {
                               if (!p.arc || p.path.empty()) return std::nullopt;
                               return p.arc->mode();
                             })
      .def_property_readonly("fallback_reason", [](const Planned& p) { return p.fallbackReason(); })
      .def_property_readonly("path", [](const Planned& p) { return toArray(p.path); })
      .def_property_readonly("waypoints", [](const Planned& p) { return p.path.size(); })
      .def_property_readonly(
          "trajectory",
          [](const Planned& p) -> std::optional<TrajectoryHandle> {
            if (!p.measurement || !p.measurement->timed) return std::nullopt;
            return TrajectoryHandle{*p.measurement->timed, p.measurement->metrics};
          },
          "The time-scaled trajectory when vmax was given, else None.")
      .def("to_dict", &toDict, "The document `arcplan plan --json` writes, as a dict with the same keys.")
      .def("__repr__", [](const Planned& p) {
        return "<arcplan.PlanResult " + p.options.planner + " on " + p.sceneName + "/" + p.queryName + ": " +
               benchmarks::toString(p.status) + ", " + std::to_string(p.path.size()) + " waypoints>";
      });
  // One property per metric, named by the metric table (tcp_path_length_m, execution_time_s, ...).
  for (const trajectory::MetricDescriptor& descriptor : trajectory::metricDescriptors()) {
    if (descriptor.member == nullptr) continue;
    result.def_property_readonly(
        descriptor.key.c_str(), [member = descriptor.member](const Planned& p) { return metricOf(p, member); },
        descriptor.label.c_str());
  }

  module.def("plan", &plan, py::arg("scene_file"), py::arg("query") = py::none(), py::arg("planner") = "arc",
             py::arg("params") = py::dict(), py::arg("seed") = py::none(), py::arg("time_limit") = 1.0,
             py::arg("vmax") = py::none(), py::arg("clearance") = 0.0,
             "Plans a scene query as `arcplan plan` does: scene_file a path, a data name or a Scene; query "
             "the query name (default: the first); planner any registry name (arc, RRTConnect, ...) with "
             "params {name: value}; seed a run seed (as `arcplan plan --seed`: OMPL's seed, samplers, simplifier and "
             "the arc planner's seed); vmax a TCP speed limit (m/s) to also "
             "time-scale the path; clearance (m) what states and motions keep, judged as bench does. A planner that "
             "finds no path gives status 'failed' and a reason.");
  module.def("planner_names", &planners::plannerNames, "Every planner name the registry knows, 'arc' first.");
}

}  // namespace arcplan::python
