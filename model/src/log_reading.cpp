#include "log_reading.h"

#include <algorithm>
#include <cmath>

#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"

namespace arcplan::model::detail {

LineReader::LineReader(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw Error("log file " + file.string() + " does not exist");
  if (std::filesystem::is_directory(file)) throw Error("log file " + file.string() + " is a directory");
  in_.open(file, std::ios::binary);
  if (!in_) throw Error("cannot read log file " + file.string());
}

bool LineReader::next(std::string& line) {
  if (!std::getline(in_, line)) return false;
  ++lineNumber_;
  return true;
}

const char* valueProblem(std::string_view field, double corruptMagnitude, double& value) {
  const auto parsed = parseDouble(field);
  if (!parsed) return "unparseable value";
  if (!std::isfinite(*parsed)) return "NaN or infinite value";
  if (std::abs(*parsed) > corruptMagnitude) return "corrupted value (magnitude above 1e12)";
  value = *parsed;
  return nullptr;
}

void DropCounter::add(const std::string& reason, std::size_t line) {
  auto it = std::find_if(dropped_.begin(), dropped_.end(), [&](const DroppedRows& d) { return d.reason == reason; });
  if (it == dropped_.end()) {
    dropped_.push_back({reason, 0, {}});
    it = std::prev(dropped_.end());
  }
  ++it->count;
  if (it->firstLines.size() < DroppedRows::kReportedLines) it->firstLines.push_back(line);
}

bool isKnownVector(const std::string& name) {
  const auto& known = knownVectorSignals();
  return std::find(known.begin(), known.end(), name) != known.end();
}

bool isKnownScalar(const std::string& name) {
  const auto& known = knownScalarSignals();
  return std::find(known.begin(), known.end(), name) != known.end();
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

bool isBlank(std::string_view line) { return trim(line).empty(); }

}  // namespace arcplan::model::detail
