#include "cli_support.h"

#include <iostream>

#include "arcplan/common/atomic_file.h"
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
  return parseNumberList(text, option, count);
}

}  // namespace arcplan::apps
