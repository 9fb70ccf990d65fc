// arcplan.bench: benchmark campaigns from Python (docs/python.md, docs/benchmarks.md). run() is `arcplan bench` and
// returns what `bench --json` writes; read_campaign() reads a finished campaign's database: its ranking (the keys of
// `bench rank --json`) and every run as a typed record per problem and planner. The GIL is released while they run.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arcplan/benchmarks/benchmark_database.h"
#include "arcplan/benchmarks/campaign.h"
#include "arcplan/benchmarks/ranking.h"
#include "arcplan/benchmarks/suite.h"
#include "bindings.h"
#include "json_objects.h"

namespace py = pybind11;

namespace arcplan::python {
namespace {

using Path = std::filesystem::path;

// A finished campaign as read back: every run and the ranking made from them.
struct Campaign {
  benchmarks::BenchmarkDatabase database;
  benchmarks::Ranking ranking;
};

Campaign readCampaign(const Path& folderOrDatabase) {
  py::gil_scoped_release release;
  const auto file = benchmarks::campaignDatabase(folderOrDatabase);
  return {benchmarks::readBenchmarkDatabase(file), benchmarks::rankDatabase(file)};
}

struct RunSettings {
  std::optional<std::vector<std::string>> planners;
  benchmarks::SuiteOverrides overrides;
};

py::object runSuite(const std::string& suiteName, const Path& out, const RunSettings& settings, unsigned workers,
                    bool plots, bool quiet, const std::string& shard) {
  benchmarks::Suite suite;
  benchmarks::CampaignOptions options;
  benchmarks::CampaignResult result;
  {
    py::gil_scoped_release release;
    suite = benchmarks::loadSuite(benchmarks::findSuite(suiteName));
    if (settings.planners) benchmarks::selectPlanners(suite, *settings.planners);
    benchmarks::applyOverrides(suite, settings.overrides);
    options.outDirectory = out;
    options.shard = benchmarks::parseShard(shard);
    options.workers = workers;
    options.plots = plots;
    options.showProgress = !quiet;
    result = benchmarks::runCampaign(suite, options);
  }
  return toPython(benchmarks::campaignSummaryJson(suite, options, result));
}

void bindRunRecords(py::module_& m) {
  py::class_<benchmarks::RunRecord>(m, "RunRecord", "One run: OMPL's `solved` and the recorded values by key.")
      .def_readonly("solved", &benchmarks::RunRecord::solved)
      .def_property_readonly("succeeded", &benchmarks::RunRecord::succeeded,
                             "solved and time-scaled (the ranking's success)")
      .def_readonly("values", &benchmarks::RunRecord::values, "metric key ('execution_time_s', ...) -> value")
      .def("value", &benchmarks::RunRecord::value, py::arg("key"), "the value when recorded and finite, else None")
      .def("__repr__", [](const benchmarks::RunRecord& r) {
        return std::string("<RunRecord ") + (r.succeeded() ? "succeeded" : r.solved ? "solved" : "failed") + ">";
      });
  py::class_<Campaign>(m, "Campaign", "A finished campaign read back from its benchmark.db.")
      .def_property_readonly("database", [](const Campaign& c) { return c.database.file; })
      .def_property_readonly(
          "runs", [](const Campaign& c) { return c.database.runs; },
          "problem -> planner -> list of RunRecord, in the order they ran")
      .def_property_readonly("families", [](const Campaign& c) { return c.database.families; })
      .def_property_readonly(
          "settings", [](const Campaign& c) { return c.database.settings; },
          "problem -> planner -> setting -> value, as the logs recorded them")
      .def_property_readonly("metrics",
                             [](const Campaign& c) {
                               std::vector<std::pair<std::string, std::string>> keys;
                               for (const auto& a : c.database.attributes) keys.emplace_back(a.key, a.label);
                               return keys;
                             })
      .def_property_readonly("experiments", [](const Campaign& c) { return toPython(c.database.experiments); })
      .def_property_readonly(
          "ranking", [](const Campaign& c) { return toPython(benchmarks::rankingJson(c.ranking)); },
          "the ranking with the keys of `bench rank --json`")
      .def("ranking_table", [](const Campaign& c) { return benchmarks::rankingTerminalTable(c.ranking); });
}

}  // namespace

void bindBenchmarks(py::module_& parent) {
  auto m = parent.def_submodule("bench", "benchmark campaigns: run a suite, read a campaign's ranking and runs");
  bindRunRecords(m);
  m.def(
      "run",
      [](const std::string& suite, const Path& out, const std::optional<std::vector<std::string>>& planners,
         std::optional<long long> runs, std::optional<double> time, std::optional<long long> budget,
         std::optional<double> vmax, unsigned workers, bool plots, bool quiet, const std::string& shard) {
        return runSuite(suite, out, {planners, {runs, time, budget, vmax}}, workers, plots, quiet, shard);
      },
      py::arg("suite") = "thesis", py::kw_only(), py::arg("out"), py::arg("planners") = py::none(),
      py::arg("runs") = py::none(), py::arg("time") = py::none(), py::arg("budget") = py::none(),
      py::arg("vmax") = py::none(), py::arg("workers") = 1, py::arg("plots") = false, py::arg("quiet") = true,
      py::arg("shard") = "1/1",
      "run a suite (built-in name or file) into `out` as `arcplan bench` does (resuming what is there); returns the "
      "campaign summary with its ranking, the keys of `bench --json`");
  m.def("read_campaign", &readCampaign, py::arg("path"), "a finished campaign folder or its benchmark.db");
}

}  // namespace arcplan::python
