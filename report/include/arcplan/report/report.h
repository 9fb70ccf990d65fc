#pragma once
// `arcplan report`: one self-contained HTML file from a benchmark campaign (folder or benchmark.db)
// or from a model session folder (session.json). See docs/report.md.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "arcplan/report/web_assets.h"

namespace arcplan::report {

// A folder with benchmark.db or a database file is a campaign, a folder with session.json a model
// session. Throws arcplan::Error saying what was expected otherwise (an unfinished campaign — logs
// but no benchmark.db — is named as such).
ReportKind detectReportKind(const std::filesystem::path& input);

// <folder>/report.html for a folder, <database folder>/report.html for a database.
std::filesystem::path defaultReportPath(const std::filesystem::path& input);

struct ReportResult {
  ReportKind kind = ReportKind::Campaign;
  std::filesystem::path file;
  std::uintmax_t bytes = 0;
  std::vector<std::string> missing;  // parts the report could not show, and why
};

// Reads the input and the web assets, then writes `output` atomically. Throws arcplan::Error before
// anything is written when the input or a library is missing.
ReportResult writeReport(const std::filesystem::path& input, const std::filesystem::path& output);

}  // namespace arcplan::report
