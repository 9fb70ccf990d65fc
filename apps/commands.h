#pragma once
// One function per subcommand of the `arcplan` executable; each lives in its own *_command.cpp,
// parses its options and calls the library.
#include <filesystem>

#include <CLI/CLI.hpp>

namespace arcplan::apps {

void registerRobotCommand(CLI::App& app);
void registerPlanCommand(CLI::App& app);
void registerScaleCommand(CLI::App& app);
void registerModelCommand(CLI::App& app);
void registerBenchCommand(CLI::App& app);
// `bench compare` and `bench baseline` (bench_compare_command.cpp), subcommands of `bench`.
void registerBenchCompareCommands(CLI::App& bench);
void registerReportCommand(CLI::App& app);

// The HTML report of a campaign folder or model session folder (report_command.cpp), for the
// `--html FILE` option of bench and model: writes it, prints its path, returns it. An empty
// `output` means report.html in the input folder.
std::filesystem::path writeHtmlReport(const std::filesystem::path& input, const std::filesystem::path& output);

}  // namespace arcplan::apps
