#pragma once
// Resolving the mesh references of a URDF: package://pkg/path through $ARCPLAN_PACKAGE_PATH and
// then $ROS_PACKAGE_PATH (colon-separated roots), then as a folder `pkg` beside the URDF file
// (descriptions shipped as one folder, e.g. MotionBenchMaker's); file:// URIs, absolute paths, and
// paths relative to the URDF file's folder. This is what lets a user load the official UR description.
#include <filesystem>
#include <string>

namespace arcplan::robot {

// Throws arcplan::Error saying which roots were searched when the file is not found.
std::filesystem::path resolveResourceUri(const std::string& uri, const std::filesystem::path& referencingFile);

}  // namespace arcplan::robot
