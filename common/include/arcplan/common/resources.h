#pragma once
// Where arcplan finds its own data (URDF, meshes, scenes, suites) and plot scripts, and where the
// reference data outside the project lives.
#include <filesystem>

namespace arcplan {

// $ARCPLAN_DATA_DIR, else the installed share/arcplan, else the source tree's data/.
std::filesystem::path dataDirectory();
// $ARCPLAN_PLOT_DIR, else share/arcplan/plot, else the source tree's scripts/plot/.
std::filesystem::path plotScriptDirectory();
// $ARCPLAN_SHARED_DATA, else ../shared/data relative to the current directory.
std::filesystem::path sharedDataDirectory();

// A relative path that names a file in the data directory ("scenes/thesis_obstacle.yaml") when
// it does not exist as given. Absolute or existing paths are returned unchanged.
std::filesystem::path resolveDataPath(const std::filesystem::path& path);

}  // namespace arcplan
