#pragma once
// Reading arcplan's YAML files (scenes, allowed-collision lists, suites, model files) with yaml-cpp
// so that every error names the file, the line and column (yaml-cpp's Mark) and the field, and says
// what was expected: "scene.yaml:5:5: obstacles[0]: unknown key 'cone'; expected one of ...".
#include <filesystem>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace arcplan {

class YamlReader {
public:
  explicit YamlReader(std::filesystem::path file) : file_(std::move(file)) {}
  const std::filesystem::path& file() const { return file_; }

  // The document; throws arcplan::Error for a missing file or malformed YAML (with its line).
  // `whatFile` names the kind of file in those messages ("scene file").
  YAML::Node load(const std::string& whatFile) const;

  // "file:line:column" of the node (or of an exception's mark), or the file alone when yaml-cpp
  // knows no position.
  std::string position(const YAML::Node& node) const;
  std::string position(const YAML::Mark& mark) const;
  [[noreturn]] void fail(const YAML::Node& node, const std::string& field, const std::string& what) const;

  // A mapping whose keys are all in `allowed`.
  void checkKeys(const YAML::Node& map, const std::string& field, const std::vector<std::string>& allowed) const;
  YAML::Node required(const YAML::Node& map, const char* key, const std::string& field) const;
  void expectSequence(const YAML::Node& node, const std::string& field) const;
  void expectMap(const YAML::Node& node, const std::string& field) const;
  std::string text(const YAML::Node& node, const std::string& field) const;
  // A plain number, or an expression such as "-pi/2" (muparser) so angles can be written exactly.
  double number(const YAML::Node& node, const std::string& field) const;
  std::vector<double> numbers(const YAML::Node& node, const std::string& field, std::size_t count) const;
  double positive(const YAML::Node& node, const std::string& field) const;
  std::vector<double> positives(const YAML::Node& node, const std::string& field, std::size_t count) const;
  // A whole number written as digits (no expression), within [minimum, maximum].
  long long wholeNumber(const YAML::Node& node, const std::string& field, long long minimum, long long maximum) const;

private:
  std::filesystem::path file_;
};

}  // namespace arcplan
