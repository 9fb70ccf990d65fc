// A simplified path is kept only where the motion validator accepts all of it
// (planners/certified_simplification.h). The plane below has one wall; which motions cross it is
// plain geometry, so the expected verdicts do not come from the code under test.
#include "arcplan/planners/certified_simplification.h"

#include "arcplan/planners/seeded_sampling.h"

#include <gtest/gtest.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathSimplifier.h>

#include <cmath>
#include <memory>
#include <utility>
#include <vector>

namespace arcplan::planners {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// The plane [-1, 3]^2 with a wall x in [0.9, 1.1], y in [-1, 2.6]: (0, 0) and (2, 0) see each other only
// around its top, e.g. through (0, 2.8) and (2, 2.8).
constexpr double kWallTop = 2.6;

bool outsideWall(const ob::State* state) {
  const auto* xy = state->as<ob::RealVectorStateSpace::StateType>();
  return !(xy->values[0] >= 0.9 && xy->values[0] <= 1.1 && xy->values[1] <= kWallTop);
}

std::shared_ptr<ob::RealVectorStateSpace> plane() {
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  space->setBounds(-1.0, 3.0);
  return space;
}

ob::SpaceInformationPtr spaceInformation(const ob::StateSpacePtr& space, bool withWall) {
  auto si = std::make_shared<ob::SpaceInformation>(space);
  if (withWall) {
    si->setStateValidityChecker(outsideWall);
  } else {
    si->setStateValidityChecker([](const ob::State*) { return true; });
  }
  si->setup();
  return si;
}

og::PathGeometric pathThrough(const ob::SpaceInformationPtr& si, const std::vector<std::pair<double, double>>& xy) {
  og::PathGeometric path(si);
  ob::ScopedState<ob::RealVectorStateSpace> state(si);
  for (const auto& [x, y] : xy) {
    state[0] = x;
    state[1] = y;
    path.append(state.get());
  }
  return path;
}

const std::vector<std::pair<double, double>> kAroundTheWall{{0, 0}, {0, 2.8}, {2, 2.8}, {2, 0}};

// Whether a motion of the path enters the wall, by sampling each segment every 0.1 mm: plain geometry,
// not OMPL's motion validator.
bool entersWall(const std::vector<std::pair<double, double>>& points) {
  for (std::size_t i = 1; i < points.size(); ++i) {
    const auto [x0, y0] = points[i - 1];
    const auto [x1, y1] = points[i];
    const int steps = 1 + static_cast<int>(std::hypot(x1 - x0, y1 - y0) / 1e-4);
    for (int k = 0; k <= steps; ++k) {
      const double t = static_cast<double>(k) / steps, x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
      if (x >= 0.9 && x <= 1.1 && y <= kWallTop) return true;
    }
  }
  return false;
}

std::vector<std::pair<double, double>> pointsOf(const og::PathGeometric& path) {
  std::vector<std::pair<double, double>> points;
  for (std::size_t i = 0; i < path.getStateCount(); ++i) {
    const auto* xy = path.getState(i)->as<ob::RealVectorStateSpace::StateType>();
    points.emplace_back(xy->values[0], xy->values[1]);
  }
  return points;
}

// The path around the wall given to simplifyKeepingCertified with a stand-in simplifier that turns it into
// `result` and reports `reported`: whether the result was kept, and the path's points afterwards.
std::pair<bool, std::vector<std::pair<double, double>>> simplifyAroundTheWallTo(
    const std::vector<std::pair<double, double>>& result, bool reported) {
  const auto si = spaceInformation(plane(), true);
  og::PathGeometric path = pathThrough(si, kAroundTheWall);
  const bool kept = simplifyKeepingCertified(*si, path, [&](og::PathGeometric& p) {
    p = pathThrough(si, result);
    return reported;
  });
  return {kept, pointsOf(path)};
}

TEST(CertifiedSimplification, JudgesEveryStateAndEveryMotion) {
  const auto si = spaceInformation(plane(), true);
  ASSERT_FALSE(entersWall(kAroundTheWall));
  EXPECT_TRUE(keepsEveryMotion(*si, pathThrough(si, kAroundTheWall)));
  EXPECT_FALSE(keepsEveryMotion(*si, pathThrough(si, {{0, 0}, {2, 0}})));          // a motion through the wall
  EXPECT_FALSE(keepsEveryMotion(*si, pathThrough(si, {{0, 0}, {1, 0}, {2, 0}})));  // a state in it
}

TEST(CertifiedSimplification, ARejectedResultGivesBackTheUnsimplifiedPath) {
  // A "simplifier" that says its straight result is fine, as OMPL's does before its own check.
  const auto [kept, points] = simplifyAroundTheWallTo({{0, 0}, {2, 0}}, true);
  EXPECT_FALSE(kept);
  EXPECT_EQ(points, kAroundTheWall);
}

TEST(CertifiedSimplification, ASimplifierThatReportsItsResultInvalidIsNotBelieved) {
  // A valid shorter path, but the simplifier returned false: the caller cannot know which part it doubts.
  const auto [kept, points] = simplifyAroundTheWallTo({{0, 0}, {0, 2.8}, {2, 0}}, false);
  EXPECT_FALSE(kept);
  EXPECT_EQ(points, kAroundTheWall);
}

TEST(CertifiedSimplification, AnAcceptedResultIsKept) {
  const std::vector<std::pair<double, double>> shorter{{0, 0}, {0.9, 2.7}, {1.1, 2.7}, {2, 0}};  // over the top
  ASSERT_FALSE(entersWall(shorter));  // the premise, checked by geometry
  const auto [kept, points] = simplifyAroundTheWallTo(shorter, true);
  EXPECT_TRUE(kept);
  EXPECT_EQ(points, shorter);
}

// OMPL's own simplifier on a SpaceInformation without the wall shortcuts through it (checked by geometry
// first); judged by the one with the wall, its result is not kept.
TEST(CertifiedSimplification, OmplSimplifiersPathThroughTheWallGivesBackTheUnsimplifiedPath) {
  const auto space = plane();
  const auto open = spaceInformation(space, false), walled = spaceInformation(space, true);
  const ob::ProblemDefinition openProblem(open);
  // Seeded (seeded_sampling.h) so the test draws the same shortcuts every time.
  og::PathGeometric alone = pathThrough(open, kAroundTheWall);
  makeSeededSimplifier(open, openProblem, 7)->simplifyMax(alone);
  ASSERT_TRUE(entersWall(pointsOf(alone))) << "the simplifier avoided the wall it cannot see: nothing tested";

  og::PathGeometric path = pathThrough(open, kAroundTheWall);
  const auto simplifier = makeSeededSimplifier(open, openProblem, 7);
  EXPECT_FALSE(simplifyKeepingCertified(*walled, path, [&](og::PathGeometric& p) {
    simplifier->simplifyMax(p);
    return true;
  }));
  EXPECT_EQ(pointsOf(path), kAroundTheWall);
}

// SimpleSetup::simplifySolution under the rule: with a simplifier that sees the wall, the solution is
// shortened and kept, and stays out of the wall.
TEST(CertifiedSimplification, SetupSolutionIsSimplifiedAndKeptWhereCertified) {
  og::SimpleSetup setup(plane());
  setup.setStateValidityChecker(outsideWall);
  setup.getSpaceInformation()->setup();
  setup.getProblemDefinition()->addSolutionPath(
      std::make_shared<og::PathGeometric>(pathThrough(setup.getSpaceInformation(), kAroundTheWall)));
  setup.getPathSimplifier() = makeSeededSimplifier(setup.getSpaceInformation(), *setup.getProblemDefinition(), 7);
  EXPECT_TRUE(simplifySolutionKeepingCertified(setup));
  const og::PathGeometric& simplified = setup.getSolutionPath();
  EXPECT_LT(simplified.length(), pathThrough(setup.getSpaceInformation(), kAroundTheWall).length());
  EXPECT_FALSE(entersWall(pointsOf(simplified)));
}

}  // namespace
}  // namespace arcplan::planners
