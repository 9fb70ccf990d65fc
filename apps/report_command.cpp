// arcplan report — one self-contained HTML file (libraries and data inlined, nothing fetched when it
// is opened) from a benchmark campaign or a model session; also behind `bench --html` and the
// model commands' `--html`.
#include <iomanip>
#include <iostream>
#include <sstream>

#include "arcplan/report/report.h"
#include "cli_support.h"
#include "commands.h"

namespace arcplan::apps {
namespace {

std::string megabytes(std::uintmax_t bytes) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(1) << static_cast<double>(bytes) / 1e6 << " MB";
  return text.str();
}

// Writes the report and tells the user where it is and what it could not show.
report::ReportResult writeAndAnnounce(const std::filesystem::path& input, const std::filesystem::path& output) {
  const auto result = report::writeReport(input, output.empty() ? report::defaultReportPath(input) : output);
  for (const auto& note : result.missing) std::cout << "report note: " << note << "\n";
  std::cout << "report: " << result.file.string() << " (" << megabytes(result.bytes) << ", open it in a web browser)\n";
  return result;
}

}  // namespace

std::filesystem::path writeHtmlReport(const std::filesystem::path& input, const std::filesystem::path& output) {
  return writeAndAnnounce(input, output).file;
}

void registerReportCommand(CLI::App& app) {
  struct ReportOptions {
    std::string input, out, json;
  };
  auto options = std::make_shared<ReportOptions>();
  auto* command = app.add_subcommand(
      "report",
      "one self-contained HTML file from a benchmark campaign (folder or benchmark.db) or a model session folder");
  command
      ->add_option("input", options->input,
                   "campaign folder, benchmark.db, or model session folder (--out of arcplan model)")
      ->required();
  command->add_option("-o,--out", options->out, "HTML file to write (default: report.html in the input folder)");
  command->add_option("--json", options->json,
                      "write {file, bytes, kind, missing} as JSON to this file ('-' for stdout)");
  command->callback([options] {
    const auto result = writeAndAnnounce(options->input, options->out);
    if (!options->json.empty()) {
      writeJson(options->json, {{"file", result.file.string()},
                                {"bytes", result.bytes},
                                {"kind", result.kind == report::ReportKind::Campaign ? "campaign" : "model_session"},
                                {"missing", result.missing}});
    }
  });
}

}  // namespace arcplan::apps
