#pragma once
// The files an HTML report is made of: the page (template, style, arcplan's scripts) from
// report/web/page, and the JavaScript libraries it inlines — plotly.js (npm, installed by
// scripts/setup with `npm ci` in report/web) and three.js with its OrbitControls (Debian's
// libjs-three). Located like the data directory (common/resources.h); nothing is fetched.
#include <filesystem>
#include <string>
#include <vector>

namespace arcplan::report {

struct InlinedScript {
  std::string name;    // "plotly.js", shown in the page's "made with" line
  std::string source;  // the file's text
};

struct WebAssets {
  std::string pageTemplate;                // page.html with the {{...}} slots
  std::string style;                       // report.css
  std::vector<InlinedScript> libraries;    // in load order
  std::vector<InlinedScript> pageScripts;  // common.js, then robot_view.js + campaign.js, model.js or comparison.js
};

enum class ReportKind { Campaign, ModelSession, Comparison };  // Comparison: bench compare --html

// $ARCPLAN_REPORT_PAGE_DIR, else share/arcplan/report installed next to the data, else the source
// tree's report/web/page.
std::filesystem::path reportPageDirectory();
// Every library file with the candidates tried, in order ($ARCPLAN_PLOTLY_JS, $ARCPLAN_THREE_DIR
// override them).
std::vector<std::filesystem::path> plotlyCandidates();
std::filesystem::path threeDirectory();

// Reads everything a report of `kind` needs. Throws arcplan::Error naming the missing file and how
// to install it (scripts/setup) when a library or page file is not there.
WebAssets loadWebAssets(ReportKind kind);

}  // namespace arcplan::report
