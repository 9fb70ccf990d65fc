#pragma once
// OMPL's PathSimplifier (1.5) can return a path with a state or motion its SpaceInformation rejects:
// it only warns ("Solution path may slightly touch on an invalid region") and returns false. Every motion
// of a planner's own path was accepted by the motion validator, so when the simplified one fails that
// check, the unsimplified path is the one that keeps the problem's clearance.
#include <functional>

#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>

namespace arcplan::planners {

// Whether every state of `path` is valid and every motion between consecutive states is accepted by
// the motion validator of `si`.
bool keepsEveryMotion(const ompl::base::SpaceInformation& si, const ompl::geometric::PathGeometric& path);

// Runs `simplify` on `path` (it returns false when it already knows its result invalid, as
// PathSimplifier::simplify does) and keeps the result only if it returned true and keepsEveryMotion;
// otherwise `path` is restored. Returns whether the simplified path was kept.
bool simplifyKeepingCertified(const ompl::base::SpaceInformation& si, ompl::geometric::PathGeometric& path,
                              const std::function<bool(ompl::geometric::PathGeometric&)>& simplify);

// SimpleSetup::simplifySolution() under the same rule: the setup's solution path is simplified by the
// setup's simplifier and restored if the result fails keepsEveryMotion. Returns whether it was kept.
bool simplifySolutionKeepingCertified(ompl::geometric::SimpleSetup& setup);

}  // namespace arcplan::planners
