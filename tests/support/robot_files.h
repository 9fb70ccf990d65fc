#pragma once
// arcplan's UR10e description as text, for tests that add links or joints to it and load or write
// the result somewhere else.
#include <regex>
#include <string>

#include "arcplan/robot/robot_model.h"
#include "support/command.h"

namespace arcplan::testing {

// data/ur10e/ur10e.urdf with its mesh references (relative to that file: filename="meshes/...") made
// absolute, so the text loads from any folder.
inline std::string ur10eUrdfText() {
  const std::string meshes = (robot::ur10eUrdfPath().parent_path() / "meshes/").string();
  return std::regex_replace(readFile(robot::ur10eUrdfPath()), std::regex("filename=\"meshes/"), "filename=\"" + meshes);
}

}  // namespace arcplan::testing
