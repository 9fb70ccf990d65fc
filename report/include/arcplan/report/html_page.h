#pragma once
// One self-contained HTML file: the page template with the style, the libraries, the report's data
// (JSON) and arcplan's scripts inlined, so it opens by double-click with no network and no server.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "arcplan/report/web_assets.h"

namespace arcplan::report {

// The page as text. `data` is embedded as JSON the scripts read (window.ARCPLAN_REPORT).
std::string renderHtmlPage(const WebAssets& assets, const std::string& title, const nlohmann::json& data);

// Renders and writes `file` atomically (a failure leaves no half-written report).
void writeHtmlPage(const std::filesystem::path& file, const WebAssets& assets, const std::string& title,
                   const nlohmann::json& data);

}  // namespace arcplan::report
