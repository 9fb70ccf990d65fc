#pragma once
// How `arcplan plan` and the benchmark campaigns treat each planner alike, so that a planner is measured on
// the same problem and the same path by both: whose solutions get OMPL's path simplifier (shortcutting)
// before they are time-scaled and measured, and what a planner with a clearance of its own keeps.
#include <ompl/base/Planner.h>

#include <string>

namespace arcplan::benchmarks {

// False for the arc planner: its path is the thesis' TCP path (lines and tangent arcs) mapped to
// joints, and shortcutting would replace the arcs by other motions. True for every other planner
// of the registry (OMPL's sampling planners return raw tree paths). Any spelling the registry accepts.
bool simplifiesSolution(const std::string& plannerName);

// Every planner plans the problem's clearance: a planner with one of its own (the arc planner's `clearance`, 1 cm
// unless set; it keeps the larger of its own and the problem's) is lowered to `clearance` where that is smaller,
// unless `clearanceGiven` (the caller set the planner's own: that stays). Other planners are left as they are.
void keepProblemClearance(ompl::base::Planner& planner, double clearance, bool clearanceGiven);

}  // namespace arcplan::benchmarks
