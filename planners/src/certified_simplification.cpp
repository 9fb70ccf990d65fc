#include "arcplan/planners/certified_simplification.h"

namespace arcplan::planners {

namespace og = ompl::geometric;

bool keepsEveryMotion(const ompl::base::SpaceInformation& si, const og::PathGeometric& path) {
  const std::size_t count = path.getStateCount();
  for (std::size_t i = 0; i < count; ++i) {
    if (!si.isValid(path.getState(i))) return false;
    if (i > 0 && !si.checkMotion(path.getState(i - 1), path.getState(i))) return false;
  }
  return true;
}

bool simplifyKeepingCertified(const ompl::base::SpaceInformation& si, og::PathGeometric& path,
                              const std::function<bool(og::PathGeometric&)>& simplify) {
  const og::PathGeometric unsimplified(path);
  if (simplify(path) && keepsEveryMotion(si, path)) return true;
  path = unsimplified;
  return false;
}

bool simplifySolutionKeepingCertified(og::SimpleSetup& setup) {
  const ompl::base::PathPtr solution = setup.getProblemDefinition()->getSolutionPath();
  if (!solution) return false;
  auto& path = static_cast<og::PathGeometric&>(*solution);
  const og::PathGeometric unsimplified(path);
  setup.simplifySolution();  // ignores the simplifier's verdict; the motion check below judges
  if (keepsEveryMotion(*setup.getSpaceInformation(), path)) return true;
  path = unsimplified;
  return false;
}

}  // namespace arcplan::planners
