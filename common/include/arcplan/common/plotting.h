#pragma once
// arcplan draws its figures with matplotlib: the C++ side writes the numbers (CSV/JSON) and runs a
// small script from plotScriptDirectory(). Plots are optional output: when no Python with
// matplotlib is found the caller reports it and carries on.
#include <optional>
#include <string>
#include <vector>

namespace arcplan {

struct PlotOutcome {
  bool ok = false;
  std::string message;  // why it failed, for the user
};

// $ARCPLAN_PYTHON, else /usr/bin/python3 (Debian's, which owns python3-matplotlib), else python3 on
// PATH; the first that imports matplotlib. Cached after the first call.
std::optional<std::string> findMatplotlibPython();

// Runs `python <plotScriptDirectory()/script> args...` without a shell and waits for it. On failure
// the message is one line: the script name, its exit code and the last line it printed (its error).
PlotOutcome runPlotScript(const std::string& script, const std::vector<std::string>& arguments);

}  // namespace arcplan
