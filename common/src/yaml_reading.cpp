#include "arcplan/common/yaml_reading.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <muParser.h>

#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"

namespace arcplan {

YAML::Node YamlReader::load(const std::string& whatFile) const {
  if (!std::filesystem::exists(file_)) throw Error(whatFile + " " + file_.string() + " does not exist");
  if (std::filesystem::is_directory(file_)) throw Error(whatFile + " " + file_.string() + " is a directory");
  try {
    return YAML::LoadFile(file_.string());
  } catch (const YAML::ParserException& e) {
    throw Error(position(e.mark) + ": malformed YAML: " + e.msg);
  } catch (const YAML::BadFile&) {
    throw Error("cannot read " + whatFile + " " + file_.string());
  }
}

std::string YamlReader::position(const YAML::Node& node) const { return position(node.Mark()); }

std::string YamlReader::position(const YAML::Mark& mark) const {
  if (mark.is_null()) return file_.string();
  return file_.string() + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

void YamlReader::fail(const YAML::Node& node, const std::string& field, const std::string& what) const {
  throw Error(position(node.Mark()) + ": " + field + ": " + what);
}

void YamlReader::checkKeys(const YAML::Node& map, const std::string& field,
                           const std::vector<std::string>& allowed) const {
  expectMap(map, field);
  for (const auto& entry : map) {
    const std::string key = entry.first.Scalar();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string list;
      for (const auto& name : allowed) list += (list.empty() ? "" : ", ") + name;
      fail(entry.first, field, "unknown key '" + key + "'; expected one of " + list);
    }
  }
}

YAML::Node YamlReader::required(const YAML::Node& map, const char* key, const std::string& field) const {
  YAML::Node node = map[key];
  if (!node) fail(map, field, std::string("missing '") + key + "'");
  return node;
}

void YamlReader::expectSequence(const YAML::Node& node, const std::string& field) const {
  if (!node.IsSequence()) fail(node, field, "expected a list");
}

void YamlReader::expectMap(const YAML::Node& node, const std::string& field) const {
  if (!node.IsMap()) fail(node, field, "expected a mapping");
}

std::string YamlReader::text(const YAML::Node& node, const std::string& field) const {
  if (!node.IsScalar() || node.Scalar().empty()) fail(node, field, "expected a non-empty string");
  return node.Scalar();
}

double YamlReader::number(const YAML::Node& node, const std::string& field) const {
  if (!node.IsScalar()) fail(node, field, "expected a number");
  const std::string& scalar = node.Scalar();
  std::optional<double> value = parseDouble(scalar);
  if (!value) {
    try {
      mu::Parser parser;
      parser.DefineConst("pi", M_PI);
      parser.SetExpr(scalar);
      value = parser.Eval();
    } catch (const mu::Parser::exception_type&) {
      fail(node, field, "expected a number or an expression like -pi/2, got '" + scalar + "'");
    }
  }
  if (!std::isfinite(*value)) fail(node, field, "expected a finite number, got '" + scalar + "'");
  return *value;
}

std::vector<double> YamlReader::numbers(const YAML::Node& node, const std::string& field, std::size_t count) const {
  if (!node.IsSequence() || node.size() != count) {
    fail(node, field,
         "expected a list of " + std::to_string(count) + " numbers" +
             (node.IsSequence() ? ", got " + std::to_string(node.size()) : std::string()));
  }
  std::vector<double> values;
  for (std::size_t i = 0; i < count; ++i) values.push_back(number(node[i], field + "[" + std::to_string(i) + "]"));
  return values;
}

double YamlReader::positive(const YAML::Node& node, const std::string& field) const {
  const double value = number(node, field);
  if (!(value > 0.0)) fail(node, field, "expected a positive number, got " + node.Scalar());
  return value;
}

std::vector<double> YamlReader::positives(const YAML::Node& node, const std::string& field, std::size_t count) const {
  const auto values = numbers(node, field, count);
  for (std::size_t i = 0; i < count; ++i) {
    if (!(values[i] > 0.0)) {
      fail(node[i], field + "[" + std::to_string(i) + "]", "expected a positive number, got " + node[i].Scalar());
    }
  }
  return values;
}

long long YamlReader::wholeNumber(const YAML::Node& node, const std::string& field, long long minimum,
                                  long long maximum) const {
  long long value = 0;
  if (!node.IsScalar() || !YAML::convert<long long>::decode(node, value)) {
    fail(node, field, "expected a whole number");
  }
  if (value < minimum || value > maximum) {
    fail(node, field, "must be between " + std::to_string(minimum) + " and " + std::to_string(maximum));
  }
  return value;
}

}  // namespace arcplan
