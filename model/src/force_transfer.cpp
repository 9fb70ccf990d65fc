#include "arcplan/model/force_transfer.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"

namespace arcplan::model {

std::vector<ForceTransferPoint> readForceTransferData(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw Error("force-transfer file " + file.string() + " does not exist");
  std::ifstream in(file);
  std::string line;
  std::size_t lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (!trim(line).empty()) break;
  }
  if (trim(line).empty()) throw Error(file.string() + " is empty: no header and no data rows");
  const auto headerFields = splitFields(line, ',');
  std::map<std::string, std::size_t> column;
  for (std::size_t c = 0; c < headerFields.size(); ++c) column[std::string(trim(headerFields[c]))] = c;
  const std::vector<std::string> required{"gearbox", "ratio", "direction", "tau_out_Nm", "tau_in_Nm"};
  for (const auto& name : required) {
    if (!column.count(name)) {
      throw Error(file.string() + ":1: missing column '" + name +
                  "' (expected gearbox, ratio, series, direction, tau_out_Nm, tau_in_Nm)");
    }
  }
  std::vector<ForceTransferPoint> points;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (trim(line).empty()) continue;
    const auto fields = splitFields(line, ',');
    const std::string where = file.string() + ":" + std::to_string(lineNumber);
    if (fields.size() != headerFields.size()) {
      throw Error(where + ": expected " + std::to_string(headerFields.size()) + " fields, got " +
                  std::to_string(fields.size()));
    }
    auto number = [&](const std::string& name) {
      const auto value = parseDouble(fields[column.at(name)]);
      if (!value || !std::isfinite(*value)) {
        throw Error(where + ": column " + name + ": '" + std::string(trim(fields[column.at(name)])) +
                    "' is not a finite number");
      }
      return *value;
    };
    ForceTransferPoint point;
    point.line = lineNumber;
    point.gearbox = std::string(trim(fields[column.at("gearbox")]));
    if (point.gearbox.empty()) throw Error(where + ": column gearbox is empty");
    point.ratio = number("ratio");
    if (point.ratio <= 0.0) throw Error(where + ": column ratio must be positive");
    if (column.count("series")) {
      const double series = number("series");
      if (series < 0 || series > 1e6 || series != std::floor(series))
        throw Error(where + ": column series: expected a small integer");
      point.series = static_cast<int>(series);
    }
    std::string direction(trim(fields[column.at("direction")]));
    std::transform(direction.begin(), direction.end(), direction.begin(), ::tolower);
    if (direction != "direct" && direction != "indirect") {
      throw Error(where + ": column direction: expected 'direct' or 'indirect', got '" + direction + "'");
    }
    point.direct = direction == "direct";
    point.outputTorque = number("tau_out_Nm");
    point.inputTorque = number("tau_in_Nm");
    points.push_back(point);
  }
  if (points.empty()) throw Error(file.string() + " has no data rows (empty log)");
  return points;
}

}  // namespace arcplan::model
