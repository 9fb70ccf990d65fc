#include "cli_support.h"

#include <cmath>
#include <iostream>

#include "arcplan/common/atomic_file.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/common/text_parsing.h"

namespace arcplan::apps {

void writeJson(const std::filesystem::path& file, const nlohmann::json& document) {
  const std::string text = document.dump(2) + "\n";
  if (file == "-") {
    std::cout << text;
    return;
  }
  writeFileAtomically(file, text);
}

std::vector<double> parseVector(const std::string& text, const std::string& option, std::size_t count) {
  try {
    return parseNumberList(text, option, count);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

void requirePositive(double value, const std::string& option, const std::string& unit) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw UsageError(option + " must be a positive number (" + unit + "), got " + formatNumber(value, 6));
  }
}

}  // namespace arcplan::apps
