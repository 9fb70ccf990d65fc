// PathCertifier: a path validated motion by motion while it grows. Expected results come from a
// fine discrete check written here (every 1e-4 rad) and from isMotionCollisionFree.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include "arcplan/collision/motion_check.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/kinematics.h"

namespace {

using namespace arcplan::collision;
using Eigen::VectorXd;

Scene thesisObstacle() { return loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml"); }

const VectorXd kSolutionA = (VectorXd(6) << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098).finished();
const VectorXd kSolutionB = (VectorXd(6) << 0.399, -1.624, 2.012, -1.958, -1.571, 0.399).finished();

// The clearance a certifier keeps (its default, passed explicitly where the tests check it).
constexpr double kClearance = 0.001;

// The smallest exact distance at 11 states along qa -> qb (4 mrad apart on the tests' 0.04 rad steps).
double closestAlong(const CollisionModel& model, CollisionData& data, const VectorXd& qa, const VectorXd& qb) {
  double closest = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= 10; ++k)
    closest = std::min(closest, distance(model, data, qa + (k / 10.0) * (qb - qa)).minimum());
  return closest;
}

bool motionCollides(const CollisionModel& model, CollisionData& data, const VectorXd& qa, const VectorXd& qb) {
  const int states = std::max(1, static_cast<int>(std::ceil((qb - qa).cwiseAbs().maxCoeff() / 1e-4)));
  for (int k = 0; k <= states; ++k) {
    if (!isCollisionFree(model, data, qa + (static_cast<double>(k) / states) * (qb - qa))) return true;
  }
  return false;
}

// A random walk of small joint steps from q: the shape of a densely sampled planner path.
std::vector<VectorXd> randomWalk(std::mt19937& random, const VectorXd& from, int steps, double stepSize) {
  std::normal_distribution<double> direction(0.0, 1.0);
  std::vector<VectorXd> path{from};
  VectorXd heading = VectorXd::Zero(6);
  for (int k = 0; k < steps; ++k) {
    for (auto& v : heading) v = 0.8 * v + direction(random);  // smooth-ish, like a curve
    path.push_back(path.back() + stepSize * heading.normalized());
  }
  return path;
}

TEST(PathCertifier, AcceptsOnlyPathsWhoseEveryMotionIsFree) {
  const auto model = makeCollisionModel(thesisObstacle());
  CollisionData data(*model), reference(*model);
  std::mt19937 random(11);
  int accepted = 0, rejected = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const auto path = randomWalk(random, trial % 2 == 0 ? kSolutionA : kSolutionB, 80, 0.04);
    PathCertifier certifier(*model, data, kClearance);
    if (!certifier.start(path.front())) continue;
    for (std::size_t i = 1; i < path.size(); ++i) {
      if (!certifier.extend(path[i])) {
        ++rejected;
        break;
      }
      ++accepted;
      ASSERT_FALSE(motionCollides(*model, reference, path[i - 1], path[i])) << "trial " << trial << " motion " << i;
      // Not just free: the certifier's budget is g − m, so every accepted motion keeps its clearance.
      ASSERT_GE(closestAlong(*model, reference, path[i - 1], path[i]), kClearance - 1e-6)
          << "trial " << trial << " motion " << i;
    }
  }
  // Both outcomes occur, or the test proves nothing.
  EXPECT_GT(accepted, 200);
  EXPECT_GT(rejected, 5);
}

TEST(PathCertifier, StopsBeforeTheFirstCollidingMotion) {
  const auto model = makeCollisionModel(thesisObstacle());
  CollisionData data(*model), reference(*model);
  // From A, the base joint turns toward the particle in 5 mrad steps until the arm hits it.
  std::vector<VectorXd> path;
  for (int k = 0; k <= 150; ++k) {
    VectorXd q = kSolutionA;
    q[0] += 0.005 * k;
    path.push_back(q);
  }
  std::optional<std::size_t> firstColliding;
  for (std::size_t i = 1; i < path.size() && !firstColliding; ++i) {
    if (motionCollides(*model, reference, path[i - 1], path[i])) firstColliding = i;
  }
  ASSERT_TRUE(firstColliding.has_value()) << "the test path must hit something";
  PathCertifier certifier(*model, data);
  ASSERT_TRUE(certifier.start(path.front()));
  std::size_t certifiedUpTo = 0;
  for (std::size_t i = 1; i < path.size() && certifier.extend(path[i]); ++i) certifiedUpTo = i;
  EXPECT_LT(certifiedUpTo, *firstColliding);
  // Conservative by at most the margin: the motions it refused come within minimumClearance.
  EXPECT_GE(certifiedUpTo + 3, *firstColliding);
}

TEST(PathCertifier, DensePathsNeedFewerMeasurementsThanWaypoints) {
  const auto model = makeCollisionModel(thesisObstacle());
  CollisionData data(*model);
  // A path 1 cm-ish per step far from everything but the table: the upper arm's 0.104 m clearance
  // covers several steps.
  VectorXd upright = kSolutionA;
  std::vector<VectorXd> path;
  for (int k = 0; k <= 100; ++k) {
    VectorXd q = upright;
    q[0] -= 0.005 * k;  // base joint, 5 mrad per step, away from the particle
    path.push_back(q);
  }
  CollisionData reference(*model);
  for (std::size_t i = 1; i < path.size(); ++i) ASSERT_FALSE(motionCollides(*model, reference, path[i - 1], path[i]));
  PathCertifier certifier(*model, data);
  ASSERT_TRUE(certifier.start(path.front()));
  for (std::size_t i = 1; i < path.size(); ++i) ASSERT_TRUE(certifier.extend(path[i])) << i;
  EXPECT_LT(certifier.measurements(), 40);
}

TEST(PathCertifier, BadInputIsAnError) {
  const auto model = makeCollisionModel(thesisObstacle());
  CollisionData data(*model);
  EXPECT_THROW(PathCertifier(*model, data, 0.0), arcplan::Error);
  PathCertifier certifier(*model, data);
  EXPECT_THROW(certifier.start(VectorXd::Zero(5)), arcplan::Error);
  ASSERT_TRUE(certifier.start(kSolutionA));
  VectorXd bad = kSolutionA;
  bad[2] = std::nan("");
  EXPECT_THROW(certifier.extend(bad), arcplan::Error);
}

}  // namespace
