#pragma once
// One function per subcommand of the `arcplan` executable; each lives in its own *_command.cpp,
// parses its options and calls the library.
#include <CLI/CLI.hpp>

namespace arcplan::apps {

void registerRobotCommand(CLI::App& app);
void registerPlanCommand(CLI::App& app);
void registerScaleCommand(CLI::App& app);
void registerModelCommand(CLI::App& app);
void registerBenchCommand(CLI::App& app);

}  // namespace arcplan::apps
