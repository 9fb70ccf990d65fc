#pragma once
// Seeded random benchmark problems for the UR10e standing on a table (the `generated` suite):
//  - line-*: start and goal are reachable tool-down poses joined by an IK-continuous straight TCP
//    line; one sphere, box or cylinder of random size sits on or near that line (the arc planner's
//    home ground: sometimes the line is free, usually a detour is needed);
//  - pillar: a floor-to-ceiling column on the line, which no arc detour of bounded height clears;
//  - shelf: a shelf unit standing between start and goal, which the tool must leave the line to pass.
// Everything is derived from the seed with arcplan's own integer-to-real mapping, so the same seed
// gives the same problems on every platform and standard library.
#include <vector>

#include "arcplan/benchmarks/suite.h"

namespace arcplan::benchmarks {

// Names "line-sphere-000", "pillar-003", ... in a fixed order. Every problem's query "main" has
// start and goal as joint vectors that are inside the joint limits and collision-free in the scene.
// Throws arcplan::Error if the generator cannot place a requested problem (never for sane settings).
std::vector<Problem> generateProblems(const GeneratorSettings& settings);

}  // namespace arcplan::benchmarks
