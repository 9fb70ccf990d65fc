#include "arcplan/common/plotting.h"

#include <cstdlib>
#include <mutex>

#include "arcplan/common/process.h"
#include "arcplan/common/resources.h"

namespace arcplan {

std::optional<std::string> findMatplotlibPython() {
  static std::once_flag once;
  static std::optional<std::string> found;
  std::call_once(once, [] {
    std::vector<std::string> candidates;
    if (const char* chosen = std::getenv("ARCPLAN_PYTHON"); chosen != nullptr && *chosen != '\0') {
      candidates.emplace_back(chosen);
    }
    candidates.emplace_back("/usr/bin/python3");
    candidates.emplace_back("python3");
    for (const auto& python : candidates) {
      if (runProcess({python, "-c", "import matplotlib"}, ProcessOutput::Discard).exitCode == 0) {
        found = python;
        return;
      }
    }
  });
  return found;
}

PlotOutcome runPlotScript(const std::string& script, const std::vector<std::string>& arguments) {
  const auto python = findMatplotlibPython();
  if (!python) {
    return {false, "no Python with matplotlib found (install python3-matplotlib or set ARCPLAN_PYTHON); plot skipped"};
  }
  const auto path = plotScriptDirectory() / script;
  std::vector<std::string> argv{*python, path.string()};
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  const int status = runProcess(argv).exitCode;
  if (status != 0) return {false, "plot script " + path.string() + " failed (exit " + std::to_string(status) + ")"};
  return {true, {}};
}

}  // namespace arcplan
