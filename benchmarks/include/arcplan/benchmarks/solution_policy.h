#pragma once
// Which planners' solutions get OMPL's path simplifier (shortcutting) before they are time-scaled
// and measured. `arcplan plan` and the benchmark campaigns both ask here, so that a planner is
// measured on the same path by both.
#include <string>

namespace arcplan::benchmarks {

// False for the arc planner: its path is the thesis' TCP path (lines and tangent arcs) mapped to
// joints, and shortcutting would replace the arcs by other motions. True for every other planner
// of the registry (OMPL's sampling planners return raw tree paths). Any spelling the registry accepts.
bool simplifiesSolution(const std::string& plannerName);

}  // namespace arcplan::benchmarks
