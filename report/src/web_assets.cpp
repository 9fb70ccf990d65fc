#include "arcplan/report/web_assets.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"

namespace arcplan::report {
namespace {

std::filesystem::path environmentPath(const char* variable) {
  const char* value = std::getenv(variable);
  return value != nullptr && *value != '\0' ? std::filesystem::path(value) : std::filesystem::path();
}

std::string readText(const std::filesystem::path& file, const std::string& whatItIs, const std::string& howToGetIt) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string() + ": " + whatItIs + " not found (" + howToGetIt + ")");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

const char* const kSetupHint = "scripts/setup installs it";

}  // namespace

std::filesystem::path reportPageDirectory() {
  if (auto fromEnvironment = environmentPath("ARCPLAN_REPORT_PAGE_DIR"); !fromEnvironment.empty())
    return fromEnvironment;
  // An installed arcplan has share/arcplan/report next to share/arcplan/ur10e.
  const auto installed = dataDirectory() / "report";
  if (std::filesystem::exists(installed / "page.html")) return installed;
  return ARCPLAN_SOURCE_REPORT_PAGE_DIR;
}

std::vector<std::filesystem::path> plotlyCandidates() {
  std::vector<std::filesystem::path> candidates;
  if (auto fromEnvironment = environmentPath("ARCPLAN_PLOTLY_JS"); !fromEnvironment.empty()) {
    candidates.push_back(fromEnvironment);
  }
  candidates.push_back(reportPageDirectory() / "plotly-cartesian.min.js");  // installed copy
  candidates.push_back(std::filesystem::path(ARCPLAN_SOURCE_REPORT_WEB_DIR) / "node_modules" /
                       "plotly.js-cartesian-dist-min" / "plotly-cartesian.min.js");
  return candidates;
}

std::filesystem::path threeDirectory() {
  if (auto fromEnvironment = environmentPath("ARCPLAN_THREE_DIR"); !fromEnvironment.empty()) return fromEnvironment;
  return "/usr/share/javascript/three";  // Debian's libjs-three
}

WebAssets loadWebAssets(ReportKind kind) {
  WebAssets assets;
  const auto page = reportPageDirectory();
  const std::string pageHint = "the report page files belong to arcplan's report/web/page";
  assets.pageTemplate = readText(page / "page.html", "report page template", pageHint);
  assets.style = readText(page / "report.css", "report style sheet", pageHint);

  std::filesystem::path plotly;
  for (const auto& candidate : plotlyCandidates()) {
    if (std::filesystem::exists(candidate)) {
      plotly = candidate;
      break;
    }
  }
  if (plotly.empty()) {
    throw Error(
        plotlyCandidates().back().string() +
        ": plotly.js not found (scripts/setup runs `npm ci` in report/web; ARCPLAN_PLOTLY_JS names another copy)");
  }
  assets.libraries.push_back({"plotly.js", readText(plotly, "plotly.js", kSetupHint)});
  if (kind == ReportKind::Campaign) {
    const auto three = threeDirectory();
    const std::string threeHint =
        "Debian package libjs-three; scripts/setup installs it, ARCPLAN_THREE_DIR names another copy";
    assets.libraries.push_back({"three.js", readText(three / "three.min.js", "three.js", threeHint)});
    assets.libraries.push_back(
        {"three.js OrbitControls",
         readText(three / "examples" / "js" / "controls" / "OrbitControls.js", "three.js OrbitControls", threeHint)});
  }
  std::vector<std::string> scripts{"common.js"};
  switch (kind) {
    case ReportKind::Campaign:
      scripts.insert(scripts.end(), {"robot_view.js", "campaign.js"});
      break;
    case ReportKind::ModelSession:
      scripts.push_back("model.js");
      break;
    case ReportKind::Comparison:
      scripts.push_back("comparison.js");
      break;
  }
  for (const auto& script : scripts) {
    assets.pageScripts.push_back({script, readText(page / script, "report script", pageHint)});
  }
  return assets;
}

}  // namespace arcplan::report
