#pragma once
// Reading arcplan's YAML files (scenes, allowed-collision lists) with yaml-cpp so that every error
// names the file, the line and column (yaml-cpp's Mark) and the field, and says what was expected.
#include <filesystem>
#include <initializer_list>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

namespace arcplan::collision::detail {

class YamlReader {
public:
  explicit YamlReader(std::filesystem::path file) : file_(std::move(file)) {}
  const std::filesystem::path& file() const { return file_; }

  // The document; throws arcplan::Error for a missing file or malformed YAML (with its line).
  YAML::Node load(const std::string& whatFile) const;

  [[noreturn]] void fail(const YAML::Node& node, const std::string& field, const std::string& what) const;
  void checkKeys(const YAML::Node& map, const std::string& field, std::initializer_list<const char*> allowed) const;
  YAML::Node required(const YAML::Node& map, const char* key, const std::string& field) const;
  void expectSequence(const YAML::Node& node, const std::string& field) const;
  void expectMap(const YAML::Node& node, const std::string& field) const;
  std::string text(const YAML::Node& node, const std::string& field) const;
  // A plain number, or an expression such as "-pi/2" (muparser) so angles can be written exactly.
  double number(const YAML::Node& node, const std::string& field) const;
  std::vector<double> numbers(const YAML::Node& node, const std::string& field, std::size_t count) const;
  double positive(const YAML::Node& node, const std::string& field) const;
  Eigen::Vector3d positiveVector(const YAML::Node& node, const std::string& field) const;

private:
  std::string position(const YAML::Mark& mark) const;
  std::filesystem::path file_;
};

}  // namespace arcplan::collision::detail
