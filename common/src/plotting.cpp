#include "arcplan/common/plotting.h"

#include <cstdlib>
#include <mutex>
#include <string_view>

#include "arcplan/common/process.h"
#include "arcplan/common/resources.h"
#include "arcplan/common/text_parsing.h"

namespace arcplan {
namespace {

// The last non-blank line of a program's output: Python's exception message ends its traceback.
std::string_view lastLine(std::string_view output) {
  output = trim(output);
  const auto newline = output.find_last_of('\n');
  return newline == std::string_view::npos ? output : trim(output.substr(newline + 1));
}

}  // namespace

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
  // Captured, so that a failing script costs the user one line (its error) instead of a traceback.
  const ProcessResult result = runProcess(argv, ProcessOutput::Capture);
  if (result.exitCode != 0) {
    const std::string_view reason = lastLine(result.output);
    return {false, script + " failed (exit " + std::to_string(result.exitCode) + ")" +
                       (reason.empty() ? std::string() : ": " + std::string(reason))};
  }
  return {true, {}};
}

}  // namespace arcplan
