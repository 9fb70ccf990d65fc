// PathCertifier: a path validated motion by motion while it grows. Expected results come from a
// fine discrete check written here (every 1e-4 rad) and from isMotionCollisionFree.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "arcplan/collision/motion_check.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/kinematics.h"
#include "support/thesis_paths.h"

namespace {

using namespace arcplan::collision;
using Eigen::VectorXd;

Scene thesisObstacle() { return loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml"); }

using arcplan::testing::bentLine;
const VectorXd& kSolutionA = arcplan::testing::kThesisSolutionA;
const VectorXd& kSolutionB = arcplan::testing::kThesisSolutionB;

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

// The smallest clearance (clearanceOf: what the per-pair rule asks, collision_model.h) at `states` + 1 states of
// qa -> qb, each measured with collision::distance: a computation independent of the certifier's bounds.
double clearanceAlong(const CollisionModel& model, CollisionData& data, const VectorXd& qa, const VectorXd& qb,
                      int states) {
  double least = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= states; ++k)
    least = std::min(least, clearanceOf(distance(model, data, qa + (static_cast<double>(k) / states) * (qb - qa))));
  return least;
}

// The waypoints of a path as expect() takes them, one per column.
Eigen::MatrixXd columns(const std::vector<VectorXd>& path) {
  Eigen::MatrixXd waypoints(path.front().size(), static_cast<Eigen::Index>(path.size()));
  for (std::size_t i = 0; i < path.size(); ++i) waypoints.col(static_cast<Eigen::Index>(i)) = path[i];
  return waypoints;
}

// The certifier's run along a path: the last waypoint it accepted (0: none after the start, -1: the start refused)
// and its measurements.
struct Certified {
  int upTo = -1, measurements = 0;
};

Certified certify(const CollisionModel& model, CollisionData& data, const std::vector<VectorXd>& path, double clearance,
                  const std::optional<Eigen::MatrixXd>& expected) {
  PathCertifier certifier(model, data, clearance);
  if (expected) certifier.expect(*expected);
  Certified run;
  if (!certifier.start(path.front())) return run;
  run.upTo = 0;
  for (std::size_t i = 1; i < path.size() && certifier.extend(path[i]); ++i) run.upTo = static_cast<int>(i);
  run.measurements = certifier.measurements();
  return run;
}

TEST(PathCertifier, EveryAcceptedMotionOfADensePathKeepsTheClearanceAtEveryState) {
  const auto model = makeCollisionModel(thesisObstacle());
  CollisionData data(*model), reference(*model);
  constexpr double kPlannerClearance = 0.01;  // the arc planner's default margin
  std::mt19937 random(23);
  int acceptedMotions = 0, refusedWithinClearance = 0, refusedKeepingIt = 0, sampled = 0, paths = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const auto path = bentLine(random, 160);  // 0.01-0.02 rad a step
    PathCertifier certifier(*model, data, kPlannerClearance);
    if (!certifier.start(path.front())) continue;
    ++paths;
    for (std::size_t i = 1; i < path.size(); ++i) {
      // 40 states a motion: at most 0.5 mrad apart, which moves no point of the arm more than ~1 mm.
      const double along = clearanceAlong(*model, reference, path[i - 1], path[i], 40);
      sampled += 41;
      if (!certifier.extend(path[i])) {
        ++(along < kPlannerClearance ? refusedWithinClearance : refusedKeepingIt);
        break;
      }
      ++acceptedMotions;
      // Self pairs keep min(c, 1 mm), obstacle pairs c: clearanceOf reports the smallest c met; GJK's 1e-6 m.
      ASSERT_GE(along, kPlannerClearance - 1e-6) << "trial " << trial << " motion " << i;
    }
  }
  EXPECT_GT(sampled, 10000);
  EXPECT_GT(acceptedMotions, 1000);
  // Paths that come within the clearance are refused, and before they do (the motions refused came within it or
  // within the acceptance margin of it).
  EXPECT_GT(refusedWithinClearance, 3);
  EXPECT_GT(paths, 20);
}

// With the path's waypoints expected (the spheres measure 8 at a time and settle most pairs), the same guarantee:
// every motion accepted keeps the clearance at 41 states measured exactly, and a path is refused at or before the first
// motion that comes within it; and the spheres spare most of the measurements.
TEST(PathCertifier, ExpectingTheWaypointsKeepsTheGuaranteeWithFewerMeasurements) {
  const auto model = makeCollisionModel(thesisObstacle());
  CollisionData data(*model), reference(*model);
  constexpr double kPlannerClearance = 0.01;
  std::mt19937 random(31);
  int acceptedMotions = 0, refusedWithin = 0, measuredExpecting = 0, measuredAlone = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const auto path = bentLine(random, 160);
    const Certified expecting = certify(*model, data, path, kPlannerClearance, columns(path));
    const Certified alone = certify(*model, data, path, kPlannerClearance, std::nullopt);
    if (expecting.upTo < 0) continue;
    std::optional<int> firstWithin;
    for (int i = 1; i < static_cast<int>(path.size()) && !firstWithin; ++i) {
      const double along = clearanceAlong(*model, reference, path[i - 1], path[i], 40);
      if (along < kPlannerClearance - 1e-6) firstWithin = i;
      if (i <= expecting.upTo) {
        ++acceptedMotions;
        ASSERT_GE(along, kPlannerClearance - 1e-6) << "trial " << trial << " motion " << i;
      }
    }
    if (firstWithin) {
      EXPECT_LT(expecting.upTo, *firstWithin) << "trial " << trial;
      ++refusedWithin;
    }
    measuredExpecting += expecting.measurements;
    measuredAlone += alone.measurements;
  }
  EXPECT_GT(acceptedMotions, 1000);
  EXPECT_GT(refusedWithin, 3);
  EXPECT_LT(2 * measuredExpecting, measuredAlone);
}

// expect() is a hint: waypoints other than the expected ones are certified exactly as without it.
TEST(PathCertifier, AnUnexpectedPathIsCertifiedAsWithoutTheHint) {
  const auto model = makeCollisionModel(thesisObstacle());
  CollisionData data(*model);
  std::mt19937 random(7);
  int accepted = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const auto path = bentLine(random, 160), other = bentLine(random, 160);
    // From its second waypoint on: every bent line starts at A, which would be expected.
    const Certified hinted =
        certify(*model, data, path, 0.01, Eigen::MatrixXd(columns(other).rightCols(other.size() - 1)));
    const Certified alone = certify(*model, data, path, 0.01, std::nullopt);
    EXPECT_EQ(hinted.upTo, alone.upTo) << "trial " << trial;
    EXPECT_EQ(hinted.measurements, alone.measurements) << "trial " << trial;
    accepted += alone.upTo;
  }
  EXPECT_GT(accepted, 300);  // the paths go far enough to compare
}

TEST(PathCertifier, APolylinePassingWithinTheClearanceIsRefusedAtOrBeforeTheMotionThatDoes) {
  const auto model = makeCollisionModel(thesisObstacle());
  CollisionData data(*model), reference(*model);
  constexpr double kPlannerClearance = 0.01;
  std::mt19937 random(5);
  int checked = 0;
  for (int trial = 0; trial < 80 && checked < 12; ++trial) {
    // Half of them with long steps (0.04-0.08 rad), where a motion may dip within the clearance between two ends
    // that keep it.
    const auto path = bentLine(random, trial % 2 == 0 ? 120 : 30);
    // The first motion that comes within the clearance, by dense sampling; paths that never do, or start within it,
    // prove nothing here.
    std::optional<std::size_t> firstWithin;
    for (std::size_t i = 1; i < path.size() && !firstWithin; ++i) {
      if (clearanceAlong(*model, reference, path[i - 1], path[i], 160) < kPlannerClearance - 1e-4) firstWithin = i;
    }
    if (!firstWithin || *firstWithin < 2) continue;
    PathCertifier certifier(*model, data, kPlannerClearance);
    ASSERT_TRUE(certifier.start(path.front()));
    std::size_t certifiedUpTo = 0;
    for (std::size_t i = 1; i < path.size() && certifier.extend(path[i]); ++i) certifiedUpTo = i;
    EXPECT_LT(certifiedUpTo, *firstWithin) << "trial " << trial;
    ++checked;
  }
  EXPECT_GE(checked, 12);
}

// Single long motions through a state within the clearance whose two ends keep it with centimetres to spare: the
// ends' certificates do not meet, and whatever settles the middle must find the dip.
TEST(PathCertifier, AMotionDippingWithinTheClearanceBetweenTwoClearEndsIsRefused) {
  const auto model = makeCollisionModel(thesisObstacle());
  CollisionData data(*model), reference(*model);
  constexpr double kPlannerClearance = 0.01;
  // Within the clearance: from A the base joint turns toward the particle until the arm is 5 mm from it.
  VectorXd within = kSolutionA;
  while (clearanceOf(distance(*model, reference, within)) >= 0.005) within[0] += 0.002;
  ASSERT_GT(within[0] - kSolutionA[0], 0.01) << "A itself must keep the clearance";
  int refused = 0;
  for (int joint = 0; joint < 4; ++joint) {
    for (const double sign : {1.0, -1.0}) {
      VectorXd direction = VectorXd::Zero(6);
      direction[joint] = sign;
      // The shortest motion through `within` along `direction` whose two ends keep 3 cm.
      std::optional<double> half;
      for (double d = 0.02; d <= 0.4 && !half; d += 0.02) {
        if (clearanceOf(distance(*model, reference, within - d * direction)) >= 0.03 &&
            clearanceOf(distance(*model, reference, within + d * direction)) >= 0.03)
          half = d;
      }
      if (!half) continue;
      const VectorXd qa = within - *half * direction, qb = within + *half * direction;
      ASSERT_LT(clearanceAlong(*model, reference, qa, qb, 400), kPlannerClearance);
      PathCertifier certifier(*model, data, kPlannerClearance);
      ASSERT_TRUE(certifier.start(qa)) << "joint " << joint;
      EXPECT_FALSE(certifier.extend(qb)) << "joint " << joint << " sign " << sign << " half " << *half;
      ++refused;
    }
  }
  EXPECT_GE(refused, 3);
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
  EXPECT_THROW(certifier.expect(Eigen::MatrixXd::Zero(5, 3)), arcplan::Error);
}

}  // namespace
