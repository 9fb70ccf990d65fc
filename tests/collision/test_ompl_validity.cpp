// OMPL glue: the joint state space, validity and clearance, the motion validator, use by a real
// OMPL planner, and calls from several threads.
#include <algorithm>
#include <cmath>
#include <random>
#include <thread>

#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include "arcplan/collision/ompl_validity.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "support/random_joint_state.h"

namespace {

using namespace arcplan::collision;
namespace ob = ompl::base;
using arcplan::robot::Vector6;

const Vector6 kSolutionA = (Vector6() << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098).finished();
const Vector6 kSolutionB = (Vector6() << 0.399, -1.624, 2.012, -1.958, -1.571, 0.399).finished();

std::shared_ptr<const CollisionModel> sceneModel(const char* name) {
  return makeCollisionModel(loadScene(arcplan::dataDirectory() / "scenes" / name));
}

ob::ScopedState<> stateOf(const ob::SpaceInformationPtr& si, const Vector6& q) {
  ob::ScopedState<> state(si);
  for (int j = 0; j < 6; ++j) state[j] = q[j];
  return state;
}

// The checkMotion overload that reports the last valid state: whether the motion is valid, and its last valid
// fraction (1 when valid).
bool checkTraced(const ob::SpaceInformationPtr& si, const ob::State* from, const ob::State* to, double& fraction) {
  ob::ScopedState<> lastValidState(si);
  std::pair<ob::State*, double> lastValid{lastValidState.get(), -1.0};
  const bool valid = si->checkMotion(from, to, lastValid);
  fraction = valid ? 1.0 : lastValid.second;
  return valid;
}

TEST(OmplValidity, JointSpaceHasTheUrdfBoundsAndNames) {
  const auto& robot = arcplan::robot::ur10e();
  const auto space = makeJointStateSpace(robot);
  ASSERT_EQ(space->getDimension(), 6u);
  const auto& bounds = space->as<ob::RealVectorStateSpace>()->getBounds();
  // facts §3: ±2pi except the elbow, ±pi.
  for (int j = 0; j < 6; ++j) {
    const double limit = j == 2 ? M_PI : 2 * M_PI;
    EXPECT_NEAR(bounds.low[j], -limit, 1e-6) << j;
    EXPECT_NEAR(bounds.high[j], limit, 1e-6) << j;
  }
  EXPECT_EQ(space->as<ob::RealVectorStateSpace>()->getDimensionName(0), "shoulder_pan_joint");
  EXPECT_EQ(space->as<ob::RealVectorStateSpace>()->getDimensionName(5), "wrist_3_joint");
}

TEST(OmplValidity, CheckerAgreesWithTheCollisionModel) {
  const auto model = sceneModel("thesis_obstacle.yaml");
  const auto si = makeSpaceInformation(model);
  CollisionData data(*model);
  EXPECT_TRUE(si->isValid(stateOf(si, kSolutionA).get()));
  Vector6 folded;
  folded << 0.0, -M_PI / 2, M_PI, 0.0, M_PI / 2, 0.0;
  EXPECT_FALSE(si->isValid(stateOf(si, folded).get()));
  // Out of bounds is invalid even where nothing collides.
  Vector6 outside = kSolutionA;
  outside[2] = 3.5;
  EXPECT_FALSE(si->isValid(stateOf(si, outside).get()));

  const auto checker = si->getStateValidityChecker();
  double clearance = -1.0;
  EXPECT_TRUE(checker->isValid(stateOf(si, kSolutionA).get(), clearance));
  // The clearance the state meets: its obstacle distance, as no self pair is closer than 1 mm (collision_model.h).
  const DistanceReport atA = distance(*model, data, kSolutionA);
  ASSERT_GE(atA.selfDistance, 0.001);
  EXPECT_DOUBLE_EQ(clearance, atA.obstacleDistance);
  EXPECT_DOUBLE_EQ(checker->clearance(stateOf(si, folded).get()), 0.0);
}

TEST(OmplValidity, MotionValidatorCatchesAnObstacleBetweenValidEndpoints) {
  // A ball where tool0 is halfway through a shoulder-pan swing from A - 0.3 rad to A + 0.3 rad:
  // both ends are 0.17 m away from it (0.566 m from the base axis times 0.3 rad), the middle hits it.
  auto scene = loadScene(arcplan::dataDirectory() / "scenes" / "thesis_free.yaml");
  Obstacle ball;
  ball.name = "ball";
  ball.radius = 0.03;
  ball.pose.translation() = arcplan::robot::tipPose(arcplan::robot::ur10e(), kSolutionA).translation();
  scene.obstacles.push_back(ball);
  const auto si = makeSpaceInformation(makeCollisionModel(scene));
  Vector6 from = kSolutionA, to = kSolutionA;
  from[0] -= 0.3;
  to[0] += 0.3;
  const auto start = stateOf(si, from), goal = stateOf(si, to);
  ASSERT_TRUE(si->isValid(start.get()));
  ASSERT_TRUE(si->isValid(goal.get()));
  EXPECT_FALSE(si->checkMotion(start.get(), goal.get()));
  EXPECT_FALSE(si->checkMotion(goal.get(), start.get()));

  ob::ScopedState<> last(si);
  std::pair<ob::State*, double> lastValid{last.get(), -1.0};
  EXPECT_FALSE(si->getMotionValidator()->checkMotion(start.get(), goal.get(), lastValid));
  // The ball (radius 0.03) plus the flange (radius ~0.045) block about ±0.13 rad around the middle.
  EXPECT_GT(lastValid.second, 0.2);
  EXPECT_LT(lastValid.second, 0.5);
  EXPECT_TRUE(si->isValid(last.get()));
  EXPECT_NEAR(last[0], from[0] + lastValid.second * 0.6, 1e-12);

  // Swinging the other way round the ball (lifting the shoulder) is free.
  Vector6 raisedFrom = from, raisedTo = to;
  raisedFrom[1] -= 0.4;
  raisedTo[1] -= 0.4;
  EXPECT_TRUE(si->checkMotion(stateOf(si, raisedFrom).get(), stateOf(si, raisedTo).get()));
}

TEST(OmplValidity, ClearanceMakesStatesAndMotionsKeepTheirDistance) {
  // A ball 0.17 m beside tool0 at A (see above); the distance query measures the state's distance d from the
  // ball, and a required clearance just below / above d accepts / rejects the state (a clearance asks it of the
  // obstacles; the arm's own pairs keep at most 1 mm, and here stay farther apart than that).
  auto scene = loadScene(arcplan::dataDirectory() / "scenes" / "thesis_free.yaml");
  Obstacle ball;
  ball.name = "ball";
  ball.radius = 0.03;
  Vector6 middle = kSolutionA;
  middle[0] += 0.3;
  ball.pose.translation() = arcplan::robot::tipPose(arcplan::robot::ur10e(), middle).translation();
  scene.obstacles.push_back(ball);
  const auto model = makeCollisionModel(scene);
  CollisionData data(*model);
  const double d = distance(*model, data, kSolutionA).obstacleDistance;
  ASSERT_GT(d, 0.05);
  const auto lenient = makeSpaceInformation(model, {}, d - 0.001);
  const auto strict = makeSpaceInformation(model, {}, d + 0.001);
  EXPECT_TRUE(lenient->isValid(stateOf(lenient, kSolutionA).get()));
  EXPECT_FALSE(strict->isValid(stateOf(strict, kSolutionA).get()));

  // Swinging toward the ball: the smallest distance along the motion, sampled densely, decides.
  Vector6 closer = kSolutionA;
  closer[0] += 0.15;
  double closest = d;
  for (int k = 0; k <= 400; ++k) {
    const DistanceReport report = distance(*model, data, kSolutionA + (closer - kSolutionA) * (k / 400.0));
    ASSERT_GE(report.selfDistance, 0.002);  // the arm's own pairs never decide here
    closest = std::min(closest, report.obstacleDistance);
  }
  ASSERT_LT(closest, d - 0.02);
  const auto loose = makeSpaceInformation(model, {}, closest - 0.005);
  const auto tight = makeSpaceInformation(model, {}, closest + 0.005);
  EXPECT_TRUE(loose->checkMotion(stateOf(loose, kSolutionA).get(), stateOf(loose, closer).get()));
  EXPECT_FALSE(tight->checkMotion(stateOf(tight, kSolutionA).get(), stateOf(tight, closer).get()));
  EXPECT_THROW(makeSpaceInformation(model, {}, -0.01), arcplan::Error);
}

// The checker keeps the states it found valid and answers them again at once (OMPL's RRTConnect asks again for
// every tree node its goal tree extends from): asked again, every state keeps its answer, and a state 1e-12 rad
// from a valid one across the clearance's edge (bisected on the line between a clear and a refused random state)
// is still measured: only the same state counts.
TEST(OmplValidity, AStateAskedAgainKeepsItsAnswer) {
  const auto model = sceneModel("thesis_obstacle.yaml");
  const auto si = makeSpaceInformation(model, {}, 0.01);
  CollisionData data(*model);
  const auto valid = [&](const Vector6& q) { return si->isValid(stateOf(si, q).get()); };
  std::mt19937_64 random(7);
  Vector6 refused;
  bool anyRefused = false;
  int edges = 0, clear = 0;
  for (int k = 0; k < 200; ++k) {
    const Vector6 q = arcplan::testing::randomJointState(model->robot(), random);
    const bool expected = hasClearance(*model, data, q, 0.01);
    ASSERT_EQ(valid(q), expected) << k;
    ASSERT_EQ(valid(q), expected) << k;  // the second time from the memo if valid
    clear += expected;
    if (!expected) {
      refused = q;
      anyRefused = true;
      continue;
    }
    if (!anyRefused) continue;
    Vector6 inside = q, outside = refused;
    for (int step = 0; step < 80 && (outside - inside).norm() > 1e-12; ++step) {
      const Vector6 middle = (inside + outside) / 2.0;
      (hasClearance(*model, data, middle, 0.01) ? inside : outside) = middle;
    }
    ASSERT_TRUE(valid(inside));
    EXPECT_FALSE(valid(outside)) << k;
    ++edges;
  }
  EXPECT_GT(clear, 20);
  EXPECT_GT(edges, 20);
}

// The motion validator remembers its answers (collision/src/answer_memo.h): asked again, each overload gives what
// isMotionCollisionFree computes for the motion (a workspace of its own, the validator's options at the problem's
// clearance), the last valid fraction included, and OMPL's counters count every call; motions 1e-12 rad apart across
// the edge of what the certificate accepts keep their own answers.
TEST(OmplValidity, AMotionAskedAgainKeepsItsAnswer) {
  const auto model = sceneModel("thesis_obstacle.yaml");
  const auto si = makeSpaceInformation(model, {}, 0.01);
  const auto* validator = dynamic_cast<const JointMotionValidator*>(si->getMotionValidator().get());
  ASSERT_NE(validator, nullptr);
  MotionCheckOptions options = validator->options();
  options.minimumClearance = 0.01;
  CollisionData data(*model);
  const auto direct = [&](const Vector6& from, const Vector6& to, double* fraction) {
    return isMotionCollisionFree(*model, data, from, to, fraction, options);
  };
  const auto traced = [&](const Vector6& from, const Vector6& to, double& fraction) {
    return checkTraced(si, stateOf(si, from).get(), stateOf(si, to).get(), fraction);
  };
  std::mt19937_64 random(11);
  std::normal_distribution<double> gaussian(0.0, 0.8);
  int refused = 0, accepted = 0, edges = 0;
  unsigned calls = 0;
  for (int k = 0; k < 500; ++k) {
    const Vector6 from = arcplan::testing::randomJointState(model->robot(), random);
    if (!hasClearance(*model, data, from, 0.01)) continue;
    Vector6 to = from;
    for (int j = 0; j < 6; ++j) to[j] += gaussian(random);
    if (!si->satisfiesBounds(stateOf(si, to).get())) continue;
    double expectedFraction = 0.0;
    const bool expected = direct(from, to, &expectedFraction);
    const bool expectedPlain = si->isValid(stateOf(si, to).get()) && direct(from, to, nullptr);
    for (int ask = 0; ask < 2; ++ask) {
      EXPECT_EQ(si->checkMotion(stateOf(si, from).get(), stateOf(si, to).get()), expectedPlain) << k;
      double fraction = -1.0;
      EXPECT_EQ(traced(from, to, fraction), expected) << k;
      if (!expected) {
        EXPECT_EQ(fraction, expectedFraction) << k;
      }
      calls += 2;
    }
    (expected ? accepted : refused) += 1;
  }
  // Refused motions cut back to the edge: an accepted motion and a refused one whose ends are 1e-12 rad apart.
  for (int k = 0; k < 400 && edges < 15; ++k) {
    const Vector6 from = arcplan::testing::randomJointState(model->robot(), random);
    if (!hasClearance(*model, data, from, 0.01)) continue;
    Vector6 to = from;
    for (int j = 0; j < 6; ++j) to[j] += gaussian(random);
    if (!si->satisfiesBounds(stateOf(si, to).get()) || direct(from, to, nullptr)) continue;
    Vector6 inside = from, outside = to;
    for (int step = 0; step < 80 && (outside - inside).norm() > 1e-12; ++step) {
      const Vector6 middle = (inside + outside) / 2.0;
      (direct(from, middle, nullptr) ? inside : outside) = middle;
    }
    if (inside == from) continue;
    const bool insidePlain = si->isValid(stateOf(si, inside).get());
    // The traced check (nothing deferred) has an edge of its own nearby: whatever it answers here, it answers again.
    double insideFraction = 0.0, outsideFraction = 0.0;
    const bool insideTraced = direct(from, inside, &insideFraction);
    const bool outsideTraced = direct(from, outside, &outsideFraction);
    for (int ask = 0; ask < 2; ++ask) {
      EXPECT_EQ(si->checkMotion(stateOf(si, from).get(), stateOf(si, inside).get()), insidePlain) << k;
      EXPECT_FALSE(si->checkMotion(stateOf(si, from).get(), stateOf(si, outside).get())) << k;
      double fraction = -1.0;
      EXPECT_EQ(traced(from, inside, fraction), insideTraced) << k;
      if (!insideTraced) {
        EXPECT_EQ(fraction, insideFraction) << k;
      }
      EXPECT_EQ(traced(from, outside, fraction), outsideTraced) << k;
      if (!outsideTraced) {
        EXPECT_EQ(fraction, outsideFraction) << k;
      }
      calls += 4;
    }
    ++edges;
  }
  EXPECT_GT(accepted, 20);
  EXPECT_GT(refused, 20);
  EXPECT_GE(edges, 10);
  EXPECT_EQ(validator->getValidMotionCount() + validator->getInvalidMotionCount(), calls);
}

TEST(OmplValidity, SegmentCountFollowsTheLargestJointStep) {
  MotionCheckOptions options;
  options.maxJointStep = 0.05;
  const auto si = makeSpaceInformation(sceneModel("thesis_free.yaml"), options);
  const auto* validator = dynamic_cast<const JointMotionValidator*>(si->getMotionValidator().get());
  ASSERT_NE(validator, nullptr);
  Vector6 to = kSolutionA;
  to[3] += 0.26;  // 5.2 steps of 0.05 rad
  to[0] -= 0.1;
  EXPECT_EQ(validator->segmentCount(stateOf(si, kSolutionA).get(), stateOf(si, to).get()), 6);
  EXPECT_EQ(validator->segmentCount(stateOf(si, kSolutionA).get(), stateOf(si, kSolutionA).get()), 1);
}

// A clearance rule that asks motions for less than the motion check's floor (1e-5 m) is refused when the
// validator is built, not later from inside OMPL's checkMotion; the floor itself is accepted.
TEST(OmplValidity, MotionValidatorRefusesARuleBelowTheMotionChecksFloor) {
  const auto si = makeSpaceInformation(sceneModel("thesis_free.yaml"));
  const auto model = sceneModel("thesis_free.yaml");
  const auto below = std::make_shared<const EndpointClearance>(0.0, 0.0);
  EXPECT_THROW(JointMotionValidator(si.get(), model, {}, below), arcplan::Error);
  const auto floor = std::make_shared<const EndpointClearance>(0.0, 1e-5);
  const JointMotionValidator validator(si.get(), model, {}, floor);
  EXPECT_TRUE(validator.checkMotion(stateOf(si, kSolutionA).get(), stateOf(si, kSolutionA).get()));
}

TEST(OmplValidity, RrtConnectSolvesAToBInTheFreeScene) {
  ompl::RNG::setSeed(7);
  const auto si = makeSpaceInformation(sceneModel("thesis_free.yaml"));
  ompl::geometric::SimpleSetup setup(si);
  setup.setStartAndGoalStates(stateOf(si, kSolutionA), stateOf(si, kSolutionB));
  setup.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(si));
  ASSERT_EQ(setup.solve(10.0), ob::PlannerStatus::EXACT_SOLUTION);
  auto& path = setup.getSolutionPath();
  ASSERT_GE(path.getStateCount(), 2u);
  for (std::size_t k = 0; k < path.getStateCount(); ++k) EXPECT_TRUE(si->isValid(path.getState(k))) << k;
  for (std::size_t k = 1; k < path.getStateCount(); ++k) {
    EXPECT_TRUE(si->checkMotion(path.getState(k - 1), path.getState(k))) << k;
  }
  // Densified to the validator's resolution, every state is collision-free too.
  path.interpolate();
  for (std::size_t k = 0; k < path.getStateCount(); ++k) EXPECT_TRUE(si->isValid(path.getState(k))) << k;
}

TEST(OmplValidity, ConcurrentCallersGetTheSequentialAnswers) {
  const auto si = makeSpaceInformation(sceneModel("thesis_obstacle.yaml"));
  std::vector<ob::ScopedState<>> states;
  for (int k = 0; k < 400; ++k) {
    ob::ScopedState<> state(si);
    state.random();
    states.push_back(state);
  }
  std::vector<int> sequential(states.size());
  for (std::size_t k = 0; k < states.size(); ++k) sequential[k] = si->isValid(states[k].get());
  std::vector<int> first(states.size()), second(states.size());
  std::vector<double> clearances(states.size());
  std::thread a([&] {
    for (std::size_t k = 0; k < states.size(); ++k) first[k] = si->isValid(states[k].get());
  });
  std::thread b([&] {
    for (std::size_t k = states.size(); k-- > 0;) {
      second[k] = si->isValid(states[k].get());
      clearances[k] = si->getStateValidityChecker()->clearance(states[k].get());
    }
  });
  a.join();
  b.join();
  EXPECT_EQ(first, sequential);
  EXPECT_EQ(second, sequential);
  for (std::size_t k = 0; k < states.size(); ++k) EXPECT_EQ(clearances[k] > 0.0, sequential[k] == 1) << k;

  // Motions, whose answers the validator remembers: two threads ask each motion of a fresh space (one computes it, the
  // other may find it remembered), both overloads, in opposite orders; the answers are those of one caller alone.
  const std::size_t motions = 150;
  const auto alone = makeSpaceInformation(sceneModel("thesis_obstacle.yaml"));
  std::vector<int> plainAlone(motions), tracedAlone(motions);
  std::vector<double> fractionAlone(motions);
  for (std::size_t k = 0; k < motions; ++k) {
    plainAlone[k] = alone->checkMotion(states[k].get(), states[k + 1].get());
    tracedAlone[k] = checkTraced(alone, states[k].get(), states[k + 1].get(), fractionAlone[k]);
  }
  const auto shared = makeSpaceInformation(sceneModel("thesis_obstacle.yaml"));
  std::vector<int> plainA(motions), plainB(motions), tracedA(motions), tracedB(motions);
  std::vector<double> fractionA(motions), fractionB(motions);
  std::thread c([&] {
    for (std::size_t k = 0; k < motions; ++k) {
      plainA[k] = shared->checkMotion(states[k].get(), states[k + 1].get());
      tracedA[k] = checkTraced(shared, states[k].get(), states[k + 1].get(), fractionA[k]);
    }
  });
  std::thread d([&] {
    for (std::size_t k = motions; k-- > 0;) {
      tracedB[k] = checkTraced(shared, states[k].get(), states[k + 1].get(), fractionB[k]);
      plainB[k] = shared->checkMotion(states[k].get(), states[k + 1].get());
    }
  });
  c.join();
  d.join();
  EXPECT_EQ(plainA, plainAlone);
  EXPECT_EQ(plainB, plainAlone);
  EXPECT_EQ(tracedA, tracedAlone);
  EXPECT_EQ(tracedB, tracedAlone);
  EXPECT_EQ(fractionA, fractionAlone);
  EXPECT_EQ(fractionB, fractionAlone);
  EXPECT_GT(std::count(plainAlone.begin(), plainAlone.end(), 0), 10);  // refused motions among them
}

}  // namespace
