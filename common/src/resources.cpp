#include "arcplan/common/resources.h"

#include <cstdlib>
#include <dlfcn.h>

namespace arcplan {
namespace {

// An installed arcplan keeps its data in <prefix>/share/arcplan next to <prefix>/lib (or bin);
// found from where this library was loaded, so the install tree can be moved. A library in the
// build tree has no such folder and falls back to the source tree.
std::filesystem::path installedDataDirectory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&installedDataDirectory), &info) == 0 || info.dli_fname == nullptr) return {};
  std::error_code ec;
  const auto library = std::filesystem::canonical(info.dli_fname, ec);
  if (ec) return {};
  // <prefix>/lib, <prefix>/lib/<multiarch> or <prefix>/bin: the prefix is at most two levels up.
  auto dir = library.parent_path();
  for (int level = 0; level < 3 && dir.has_relative_path(); ++level, dir = dir.parent_path()) {
    const auto candidate = dir / "share" / "arcplan";
    if (std::filesystem::exists(candidate / "ur10e" / "ur10e.urdf")) return candidate;
  }
  return {};
}

std::filesystem::path firstExisting(const char* environmentVariable, const std::filesystem::path& installed,
                                    const char* source) {
  if (const char* value = std::getenv(environmentVariable); value != nullptr && *value != '\0') return value;
  if (!installed.empty() && std::filesystem::exists(installed)) return installed;
  return source;
}

}  // namespace

std::filesystem::path dataDirectory() {
  return firstExisting("ARCPLAN_DATA_DIR", installedDataDirectory(), ARCPLAN_SOURCE_DATA_DIR);
}

std::filesystem::path plotScriptDirectory() {
  const auto installed = installedDataDirectory();
  return firstExisting("ARCPLAN_PLOT_DIR", installed.empty() ? installed : installed / "plot", ARCPLAN_SOURCE_PLOT_DIR);
}

std::filesystem::path sharedDataDirectory() {
  if (const char* value = std::getenv("ARCPLAN_SHARED_DATA"); value != nullptr && *value != '\0') return value;
  return std::filesystem::path("..") / "shared" / "data";
}

std::filesystem::path resolveDataPath(const std::filesystem::path& path) {
  if (path.is_absolute() || std::filesystem::exists(path)) return path;
  const auto inData = dataDirectory() / path;
  return std::filesystem::exists(inData) ? inData : path;
}

}  // namespace arcplan
