#include "arcplan/report/report.h"

#include "arcplan/common/error.h"
#include "arcplan/report/campaign_report.h"
#include "arcplan/report/html_page.h"
#include "arcplan/report/model_session_report.h"

namespace arcplan::report {

ReportKind detectReportKind(const std::filesystem::path& input) {
  if (!std::filesystem::exists(input))
    throw Error(input.string() +
                ": no such file or folder (expected a campaign folder, a benchmark.db or a model session folder)");
  if (std::filesystem::is_regular_file(input)) return ReportKind::Campaign;  // a database; rankDatabase checks it
  if (std::filesystem::exists(input / "benchmark.db")) return ReportKind::Campaign;
  if (std::filesystem::exists(input / "session.json")) return ReportKind::ModelSession;
  if (std::filesystem::exists(input / "campaign.json") || std::filesystem::exists(input / "logs")) {
    throw Error(input.string() +
                ": campaign without benchmark.db (unfinished: rerun the same arcplan bench command, or "
                "arcplan bench rank --logs " +
                (input / "logs").string() + " --db " + (input / "benchmark.db").string() + ")");
  }
  throw Error(input.string() + ": neither a campaign folder (benchmark.db) nor a model session folder (session.json)");
}

std::filesystem::path defaultReportPath(const std::filesystem::path& input) {
  const auto folder = std::filesystem::is_directory(input) ? input : input.parent_path();
  return folder / "report.html";
}

ReportResult writeReport(const std::filesystem::path& input, const std::filesystem::path& output) {
  ReportResult result;
  result.kind = detectReportKind(input);
  const auto assets = loadWebAssets(result.kind);  // before the data: a missing library fails fast
  const auto data =
      result.kind == ReportKind::Campaign ? campaignReportData(input, output) : modelSessionReportData(input);
  std::string title;
  if (result.kind == ReportKind::Campaign) {
    const auto folder = std::filesystem::is_directory(input) ? input : input.parent_path();
    title = "arcplan benchmark report — " + std::filesystem::absolute(folder).lexically_normal().filename().string();
  } else {
    title = "arcplan model session — " + std::filesystem::absolute(input).lexically_normal().filename().string();
  }
  writeHtmlPage(output, assets, title, data);
  for (const auto& message : data.at("missing")) result.missing.push_back(message.get<std::string>());
  result.file = output;
  result.bytes = std::filesystem::file_size(output);
  return result;
}

}  // namespace arcplan::report
