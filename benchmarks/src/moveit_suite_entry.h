#pragma once
// Internal to suite.cpp: the suite key `moveit_problems: {folder, urdf, srdf}` (moveit_problems.h).
#include "arcplan/benchmarks/suite.h"
#include "arcplan/common/yaml_reading.h"

namespace arcplan::benchmarks::detail {

// Reads the entry (paths relative to the suite file, else under ARCPLAN_SHARED_DATA; a missing folder
// says where it looked) and adds its problems to `suite`. Errors of a problem file name that file.
void addMoveItSuiteEntry(const YamlReader& suiteFile, const YAML::Node& entry, Suite& suite);

}  // namespace arcplan::benchmarks::detail
