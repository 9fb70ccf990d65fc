#include "arcplan/robot/package_path.h"

#include <cstdlib>
#include <optional>
#include <vector>

#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"

namespace arcplan::robot {
namespace {

std::vector<std::filesystem::path> searchRoots(const char* variable) {
  std::vector<std::filesystem::path> roots;
  const char* value = std::getenv(variable);
  if (value == nullptr) return roots;
  for (const auto entry : splitFields(value, ':')) {
    if (!entry.empty()) roots.emplace_back(std::string(entry));
  }
  return roots;
}

// A ROS package root either contains the package folder or is the package folder itself.
std::optional<std::filesystem::path> findInRoots(const std::vector<std::filesystem::path>& roots,
                                                 const std::string& package, const std::string& rest) {
  for (const auto& root : roots) {
    const auto inside = root / package / rest;
    if (std::filesystem::exists(inside)) return inside;
    if (root.filename() == package && std::filesystem::exists(root / rest)) return root / rest;
  }
  return std::nullopt;
}

std::string describe(const std::vector<std::filesystem::path>& roots) {
  if (roots.empty()) return "unset";
  std::string text;
  for (const auto& r : roots) text += (text.empty() ? "" : ":") + r.string();
  return text;
}

}  // namespace

std::filesystem::path resolveResourceUri(const std::string& uri, const std::filesystem::path& referencingFile) {
  const std::string packagePrefix = "package://";
  const std::string filePrefix = "file://";
  if (uri.rfind(packagePrefix, 0) == 0) {
    const std::string rest = uri.substr(packagePrefix.size());
    const auto slash = rest.find('/');
    if (slash == std::string::npos || slash == 0)
      throw Error("malformed resource URI '" + uri + "' (expected package://<package>/<path>)");
    const std::string package = rest.substr(0, slash);
    const std::string path = rest.substr(slash + 1);
    const auto arcplanRoots = searchRoots("ARCPLAN_PACKAGE_PATH");
    const auto rosRoots = searchRoots("ROS_PACKAGE_PATH");
    if (auto found = findInRoots(arcplanRoots, package, path)) return *found;
    if (auto found = findInRoots(rosRoots, package, path)) return *found;
    // Descriptions shipped as one folder (MotionBenchMaker's, robowflex_resources) name a subfolder
    // of their own folder as the package.
    const std::filesystem::path beside = referencingFile.parent_path() / package / path;
    if (!referencingFile.empty() && std::filesystem::exists(beside)) return beside;
    throw Error("mesh '" + uri + "' not found: package '" + package + "' searched in ARCPLAN_PACKAGE_PATH (" +
                describe(arcplanRoots) + "), ROS_PACKAGE_PATH (" + describe(rosRoots) + ") and beside " +
                (referencingFile.empty() ? std::string("the referencing file") : referencingFile.string()));
  }
  std::filesystem::path path =
      uri.rfind(filePrefix, 0) == 0 ? std::filesystem::path(uri.substr(filePrefix.size())) : std::filesystem::path(uri);
  if (path.is_relative()) path = referencingFile.parent_path() / path;
  if (!std::filesystem::exists(path)) throw Error("mesh '" + uri + "' not found (looked for " + path.string() + ")");
  return path;
}

}  // namespace arcplan::robot
