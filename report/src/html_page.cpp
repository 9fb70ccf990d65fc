#include "arcplan/report/html_page.h"

#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"

namespace arcplan::report {
namespace {

// Inside <script>, the HTML parser ends the element at the first "</script" whatever the JavaScript
// means; "<\/" is the same text for JSON and for JavaScript strings, so every "</" is escaped.
std::string scriptSafe(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out += '\\';
  }
  return out;
}

std::string htmlEscaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Slots are filled in document order, the search starting after the previous insertion, so a "{{"
// inside the data or a library is never taken for a slot.
void fillSlot(std::string& page, std::size_t& from, const std::string& slot, const std::string& content) {
  const std::string marker = "{{" + slot + "}}";
  const auto at = page.find(marker, from);
  if (at == std::string::npos) throw Error("report page template: slot " + marker + " missing or out of order");
  page.replace(at, marker.size(), content);
  from = at + content.size();
}

std::string scriptElements(const std::vector<InlinedScript>& scripts) {
  std::string out;
  for (const auto& script : scripts) {
    out += "<script data-name=\"" + htmlEscaped(script.name) + "\">\n" + scriptSafe(script.source) + "\n</script>\n";
  }
  return out;
}

}  // namespace

std::string renderHtmlPage(const WebAssets& assets, const std::string& title, const nlohmann::json& data) {
  std::string libraryNames;
  for (const auto& library : assets.libraries) libraryNames += (libraryNames.empty() ? "" : ", ") + library.name;
  std::string page = assets.pageTemplate;
  std::size_t from = 0;
  fillSlot(page, from, "TITLE", htmlEscaped(title));
  fillSlot(page, from, "STYLE", assets.style);
  fillSlot(page, from, "HEADING", htmlEscaped(title));
  fillSlot(page, from, "LIBRARY_NAMES", htmlEscaped(libraryNames));
  fillSlot(page, from, "DATA",
           "<script id=\"report-data\" type=\"application/json\">" +
               scriptSafe(data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)) + "</script>");
  fillSlot(page, from, "SCRIPTS", scriptElements(assets.libraries) + scriptElements(assets.pageScripts));
  return page;
}

void writeHtmlPage(const std::filesystem::path& file, const WebAssets& assets, const std::string& title,
                   const nlohmann::json& data) {
  AtomicOutputFile out(file);
  out.stream() << renderHtmlPage(assets, title, data);
  out.commit();
}

}  // namespace arcplan::report
