// arcplan: planning, collision checking, time scaling, benchmarks and model validation for the UR10e.
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
  CLI::App app{"arcplan — arc obstacle-avoidance planning, FCL collision checking and TCP-speed time scaling "
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
