#include "arcplan/common/text_parsing.h"

#include <charconv>
#include <cmath>

#include "arcplan/common/error.h"

namespace arcplan {

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

std::optional<double> parseDouble(std::string_view text) {
  text = trim(text);
  if (text.empty()) return std::nullopt;
  if (text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::vector<std::string_view> splitFields(std::string_view line, char separator) {
  std::vector<std::string_view> fields;
  if (separator == ' ') {
    std::size_t pos = 0;
    while (pos < line.size()) {
      const auto start = line.find_first_not_of(" \t\r", pos);
      if (start == std::string_view::npos) break;
      const auto stop = line.find_first_of(" \t\r", start);
      fields.push_back(line.substr(start, stop == std::string_view::npos ? std::string_view::npos : stop - start));
      pos = stop == std::string_view::npos ? line.size() : stop;
    }
    return fields;
  }
  std::size_t start = 0;
  while (true) {
    const auto stop = line.find(separator, start);
    fields.push_back(line.substr(start, stop == std::string_view::npos ? std::string_view::npos : stop - start));
    if (stop == std::string_view::npos) break;
    start = stop + 1;
  }
  return fields;
}

std::vector<double> parseNumberList(std::string_view text, const std::string& what, std::size_t expectedCount) {
  std::vector<double> values;
  for (const auto field : splitFields(text, ',')) {
    const auto value = parseDouble(field);
    if (!value || !std::isfinite(*value)) {
      throw Error(what + ": '" + std::string(trim(field)) + "' is not a finite number");
    }
    values.push_back(*value);
  }
  if (expectedCount > 0 && values.size() != expectedCount) {
    throw Error(what + ": expected " + std::to_string(expectedCount) + " comma-separated numbers, got " +
                std::to_string(values.size()));
  }
  return values;
}

}  // namespace arcplan
