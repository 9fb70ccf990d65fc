// arcplan: planning, collision checking, time scaling, benchmarks and model validation for the UR10e.
#include <malloc.h>

#include <climits>
#include <string>

#include <CLI/CLI.hpp>

#include "command_line.h"
#include "commands.h"
#include "exit_codes.h"

namespace {

// `arcplan --help` ends with the exit codes, from the one table of them.
std::string exitCodeFooter() {
  std::string text = "Exit codes:";
  for (const auto& entry : arcplan::apps::kExitCodes) {
    text += "\n  " + std::to_string(arcplan::apps::toInt(entry.code)) + "  " + entry.meaning;
  }
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  // The model commands allocate and free matrices of tens of MB per candidate effect on long logs. glibc
  // serves blocks that big with mmap and unmaps them on free, so each new one page-faults again: on a
  // 1.8 M-row log that was two thirds of `model diagnose`'s CPU time (docs/model.md, "Big logs").
  // Keeping them in the heap, never trimmed, reuses the pages; the peak stays the same.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
  CLI::App app{
      "arcplan — arc obstacle-avoidance planning, FCL collision checking and TCP-speed time scaling "
      "for the UR10e, OMPL benchmarks, and robot models checked against measurements",
      "arcplan"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(ARCPLAN_VERSION));
  app.footer(exitCodeFooter());
  arcplan::apps::registerRobotCommand(app);
  arcplan::apps::registerPlanCommand(app);
  arcplan::apps::registerScaleCommand(app);
  arcplan::apps::registerModelCommand(app);
  arcplan::apps::registerBenchCommand(app);
  arcplan::apps::registerReportCommand(app);
  return arcplan::apps::runCommandLine(app, argc, argv);
}
