#include "json_file.h"

#include <fstream>

#include "arcplan/common/error.h"

namespace arcplan::report::detail {

nlohmann::json readJsonFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw Error(file.string() + ": cannot open");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(file.string() + ": not valid JSON (" + e.what() + ")");
  }
}

}  // namespace arcplan::report::detail
