// Certified motion checks (motion_check.h) against an independent reference written here: a fine
// discrete check (states 1e-4 rad apart, isCollisionFree) and sampled clearances. Soundness on random
// motions of the thesis scene and with particles placed on a link's path (one of them a particle the
// old 0.01 rad discrete check tunnels through), acceptance of motions with clearance, the last valid
// state, the motion bounds against measured mesh-vertex displacements, OMPL planning with the
// certified validator, and bad options.
// Over 400 lines because every test here shares the one independent reference above (fine discrete
// check, sampled clearance, mesh vertices per link); splitting would mean a header of test internals.
#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include "arcplan/collision/joint_states.h"
#include "arcplan/collision/motion_check.h"
#include "arcplan/collision/ompl_validity.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/mesh.h"
#include "support/thesis_paths.h"
#include "motion_bounds.h"  // collision/src: the bounds behind the certified check

namespace {

using namespace arcplan::collision;
using Eigen::VectorXd;
namespace ob = ompl::base;

Scene thesisScene(const char* name) { return loadScene(arcplan::dataDirectory() / "scenes" / name); }

const VectorXd& kSolutionA = arcplan::testing::kThesisSolutionA;
const VectorXd& kSolutionB = arcplan::testing::kThesisSolutionB;

VectorXd along(const VectorXd& qa, const VectorXd& qb, double s) { return qa + s * (qb - qa); }

// The reference: states at most `step` rad (largest joint change) apart, ends included; the fraction
// of the first colliding one. With 1e-4 rad no point of the UR10e moves more than ~0.4 mm between
// two states (the sum of its joints' reaches is below 4 m).
std::optional<double> firstCollision(const CollisionModel& model, CollisionData& data, const VectorXd& qa,
                                     const VectorXd& qb, double step = 1e-4) {
  const int states = std::max(1, static_cast<int>(std::ceil((qb - qa).cwiseAbs().maxCoeff() / step)));
  for (int k = 0; k <= states; ++k) {
    const double s = static_cast<double>(k) / states;
    if (!isCollisionFree(model, data, along(qa, qb, s))) return s;
  }
  return std::nullopt;
}

// Smallest distance of any pair (obstacle or self) over states 1e-3 rad apart: a motion that keeps more than a
// clearance by this keeps it under any reading of the clearance.
double sampledClearance(const CollisionModel& model, CollisionData& data, const VectorXd& qa, const VectorXd& qb) {
  const int states = std::max(1, static_cast<int>(std::ceil((qb - qa).cwiseAbs().maxCoeff() / 1e-3)));
  double clearance = INFINITY;
  for (int k = 0; k <= states; ++k) {
    clearance = std::min(clearance, distance(model, data, along(qa, qb, static_cast<double>(k) / states)).minimum());
  }
  return clearance;
}

struct Motion {
  VectorXd start, end;
};

// A collision-free random start and an end in a random direction whose largest joint change is
// drawn from [smallest, largest] rad, inside the joint limits (and collision-free if `freeEnd`).
Motion randomMotion(const CollisionModel& model, CollisionData& data, std::mt19937_64& random, double smallest,
                    double largest, bool freeEnd) {
  const auto& joints = model.robot().joints();
  std::normal_distribution<double> gaussian;
  while (true) {
    VectorXd start(6), direction(6);
    for (int j = 0; j < 6; ++j) {
      start[j] = std::uniform_real_distribution<double>(joints[j].limits.lower, joints[j].limits.upper)(random);
      direction[j] = gaussian(random);
    }
    const double step = std::uniform_real_distribution<double>(smallest, largest)(random);
    const VectorXd end = start + step / direction.cwiseAbs().maxCoeff() * direction;
    bool inside = true;
    for (int j = 0; j < 6; ++j) inside = inside && end[j] >= joints[j].limits.lower && end[j] <= joints[j].limits.upper;
    if (!inside || !isCollisionFree(model, data, start)) continue;
    if (freeEnd && !isCollisionFree(model, data, end)) continue;
    return {start, end};
  }
}

// The collision-mesh vertices of every link with geometry (model.linkNames() order) in its link
// frame, loaded here from the URDF's files rather than taken from the collision model.
std::vector<std::vector<Eigen::Vector3d>> linkVertices(const CollisionModel& model) {
  std::vector<std::vector<Eigen::Vector3d>> result;
  for (const auto& name : model.linkNames()) {
    std::vector<Eigen::Vector3d> vertices;
    for (const auto& geometry : model.robot().links()[model.robot().linkIndex(name)].collisions) {
      EXPECT_EQ(geometry.shape, arcplan::robot::CollisionGeometry::Shape::Mesh) << name;
      for (const auto& v : arcplan::robot::loadMesh(geometry.meshFile, geometry.meshScale).vertices) {
        vertices.push_back(geometry.origin * v);
      }
    }
    result.push_back(std::move(vertices));
  }
  return result;
}

int commonAncestor(const arcplan::robot::RobotModel& robot, int a, int b) {
  std::vector<int> ancestorsOfA;
  for (int l = a; l >= 0; l = robot.links()[l].parent) ancestorsOfA.push_back(l);
  for (int l = b; l >= 0; l = robot.links()[l].parent) {
    if (std::find(ancestorsOfA.begin(), ancestorsOfA.end(), l) != ancestorsOfA.end()) return l;
  }
  return 0;
}

Obstacle particleAt(const Eigen::Vector3d& centre, double radius = 0.01) {
  Obstacle particle;
  particle.name = "grain";
  particle.shape = Obstacle::Shape::Sphere;
  particle.radius = radius;
  particle.pose.translation() = centre;
  return particle;
}

MotionCheckOptions discreteOptions(double maxJointStep) {
  MotionCheckOptions options;
  options.method = MotionCheck::Discrete;
  options.maxJointStep = maxJointStep;
  return options;
}

TEST(CertifiedMotionCheck, NeverAcceptsAMotionTheFineCheckFindsColliding) {
  const auto model = makeCollisionModel(thesisScene("thesis_obstacle.yaml"));
  CollisionData data(*model);
  std::mt19937_64 random(41);
  int colliding = 0, free = 0;
  for (int trial = 0; trial < 80; ++trial) {
    const Motion motion = randomMotion(*model, data, random, 0.2, 1.2, false);
    const std::optional<double> collision = firstCollision(*model, data, motion.start, motion.end);
    const bool certified = isMotionCollisionFree(*model, data, motion.start, motion.end);
    double lastValid = -1.0;
    const bool fromStart = isMotionCollisionFree(*model, data, motion.start, motion.end, &lastValid);
    if (collision) {
      ++colliding;
      EXPECT_FALSE(certified) << trial;
      EXPECT_FALSE(fromStart) << trial;
      // The last valid state lies before the first collision, and the motion up to it is free.
      EXPECT_GE(lastValid, 0.0) << trial;
      EXPECT_LT(lastValid, *collision) << trial;
      EXPECT_FALSE(firstCollision(*model, data, motion.start, along(motion.start, motion.end, lastValid))) << trial;
    } else {
      ++free;
    }
  }
  // Both kinds occur, so the assertions above were exercised.
  EXPECT_GE(colliding, 10);
  EXPECT_GE(free, 10);
}

TEST(CertifiedMotionCheck, CatchesParticlesPlacedOnALinksPath) {
  const Scene base = thesisScene("thesis_free.yaml");
  const auto baseModel = makeCollisionModel(base);
  CollisionData baseData(*baseModel);
  const auto vertices = linkVertices(*baseModel);
  arcplan::robot::KinematicsData kinematics(baseModel->robot());
  std::mt19937_64 random(17);
  int placed = 0;
  for (int trial = 0; placed < 12 && trial < 100; ++trial) {
    const Motion motion = randomMotion(*baseModel, baseData, random, 0.3, 1.0, true);
    // A 1 cm particle centred on a vertex of a moving link where the motion is half done.
    const int body = 1 + static_cast<int>(random() % (vertices.size() - 1));  // not the fixed base
    const auto& linkVertex = vertices[body][random() % vertices[body].size()];
    arcplan::robot::forwardKinematics(baseModel->robot(), along(motion.start, motion.end, 0.5), kinematics);
    const int link = baseModel->robot().linkIndex(baseModel->linkNames()[body]);
    Scene scene = base;
    scene.obstacles.push_back(particleAt(kinematics.linkPoses[link] * linkVertex));
    const auto model = makeCollisionModel(scene);
    CollisionData data(*model);
    if (!isCollisionFree(*model, data, motion.start) || !isCollisionFree(*model, data, motion.end)) continue;
    ++placed;
    const std::optional<double> collision = firstCollision(*model, data, motion.start, motion.end);
    ASSERT_TRUE(collision) << trial;  // the particle contains a point of the link at s = 0.5
    EXPECT_FALSE(isMotionCollisionFree(*model, data, motion.start, motion.end)) << trial;
    double lastValid = -1.0;
    EXPECT_FALSE(isMotionCollisionFree(*model, data, motion.start, motion.end, &lastValid)) << trial;
    EXPECT_GE(lastValid, 0.0) << trial;
    EXPECT_LT(lastValid, *collision) << trial;
    EXPECT_TRUE(isCollisionFree(*model, data, along(motion.start, motion.end, lastValid))) << trial;
  }
  EXPECT_EQ(placed, 12);
}

TEST(CertifiedMotionCheck, CatchesAParticleTheDiscreteCheckTunnelsThrough) {
  // Seeded motions of 30 discrete segments (largest joint change 0.3 rad, 0.01 rad steps). Between
  // states 15 and 16 the fastest mesh vertex passes a 1 cm particle placed beside its path (1 mm
  // into it, off the link sideways), so only a short stretch of the motion touches the particle;
  // the first such motion the 0.01 rad discrete check accepts is the tunnelling case.
  const Scene base = thesisScene("thesis_free.yaml");
  const auto baseModel = makeCollisionModel(base);
  CollisionData baseData(*baseModel);
  const auto& robot = baseModel->robot();
  const auto vertices = linkVertices(*baseModel);
  arcplan::robot::KinematicsData before(robot), middle(robot), after(robot);
  const double crossing = 15.5 / 30.0;
  std::mt19937_64 random(3);
  std::shared_ptr<const CollisionModel> model;
  Motion motion;
  for (int trial = 0; !model && trial < 60; ++trial) {
    motion = randomMotion(*baseModel, baseData, random, 0.3, 0.3, true);
    arcplan::robot::forwardKinematics(robot, along(motion.start, motion.end, crossing - 1e-6), before);
    arcplan::robot::forwardKinematics(robot, along(motion.start, motion.end, crossing), middle);
    arcplan::robot::forwardKinematics(robot, along(motion.start, motion.end, crossing + 1e-6), after);
    Eigen::Vector3d point = Eigen::Vector3d::Zero(), velocity = Eigen::Vector3d::UnitX(), outward = velocity;
    double fastest = -1.0;
    for (std::size_t body = 0; body < vertices.size(); ++body) {
      const int link = robot.linkIndex(baseModel->linkNames()[body]);
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (const auto& v : vertices[body]) centroid += middle.linkPoses[link] * v;
      centroid /= static_cast<double>(vertices[body].size());
      for (const auto& v : vertices[body]) {
        const Eigen::Vector3d moved = after.linkPoses[link] * v - before.linkPoses[link] * v;
        if (moved.norm() > fastest) {
          fastest = moved.norm();
          point = middle.linkPoses[link] * v;
          velocity = moved.normalized();
          outward = point - centroid;
        }
      }
    }
    outward = (outward - outward.dot(velocity) * velocity).normalized();
    Scene scene = base;
    scene.obstacles.push_back(particleAt(point + (0.01 - 0.001) * outward));
    auto candidate = makeCollisionModel(scene);
    CollisionData data(*candidate);
    if (!isCollisionFree(*candidate, data, motion.start) || !isCollisionFree(*candidate, data, motion.end)) continue;
    if (isMotionCollisionFree(*candidate, data, motion.start, motion.end, nullptr, discreteOptions(0.01))) {
      model = candidate;
    }
  }
  ASSERT_TRUE(model) << "no motion tunnels through its particle";
  CollisionData data(*model);
  const std::optional<double> collision = firstCollision(*model, data, motion.start, motion.end);
  ASSERT_TRUE(collision);  // the particle contains a point of the link at the crossing
  EXPECT_FALSE(isMotionCollisionFree(*model, data, motion.start, motion.end));
  double lastValid = -1.0;
  EXPECT_FALSE(isMotionCollisionFree(*model, data, motion.start, motion.end, &lastValid));
  EXPECT_GE(lastValid, 0.0);
  EXPECT_LT(lastValid, *collision);

  // The same through OMPL: the discrete validator (0.01 rad) accepts, the default one rejects and
  // hands back a valid state before the particle.
  const auto discrete = makeSpaceInformation(model, discreteOptions(0.01));
  const auto certified = makeSpaceInformation(model);
  ob::ScopedState<> start(certified), goal(certified), last(certified);
  for (int j = 0; j < 6; ++j) {
    start[j] = motion.start[j];
    goal[j] = motion.end[j];
  }
  EXPECT_TRUE(discrete->checkMotion(start.get(), goal.get()));
  EXPECT_FALSE(certified->checkMotion(start.get(), goal.get()));
  std::pair<ob::State*, double> lastState{last.get(), -1.0};
  EXPECT_FALSE(certified->getMotionValidator()->checkMotion(start.get(), goal.get(), lastState));
  EXPECT_GE(lastState.second, 0.0);
  EXPECT_LT(lastState.second, *collision);
  EXPECT_TRUE(certified->isValid(last.get()));
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(last[j], along(motion.start, motion.end, lastState.second)[j], 1e-12);
}

TEST(CertifiedMotionCheck, AcceptsMotionsWithClearance) {
  // Clearance sampled every 1e-3 rad at least 2 cm: no point moves 4 mm between samples, so the
  // motion keeps more than 1.6 cm, far above minimumClearance (1 mm).
  const auto model = makeCollisionModel(thesisScene("thesis_obstacle.yaml"));
  CollisionData data(*model);
  std::mt19937_64 random(29);
  int accepted = 0;
  for (int trial = 0; accepted < 15 && trial < 200; ++trial) {
    const Motion motion = randomMotion(*model, data, random, 0.2, 1.0, true);
    if (sampledClearance(*model, data, motion.start, motion.end) < 0.02) continue;
    ++accepted;
    EXPECT_TRUE(isMotionCollisionFree(*model, data, motion.start, motion.end)) << trial;
    double lastValid = -1.0;
    EXPECT_TRUE(isMotionCollisionFree(*model, data, motion.start, motion.end, &lastValid)) << trial;
    EXPECT_EQ(lastValid, -1.0) << "untouched on success";
  }
  EXPECT_EQ(accepted, 15);
}

TEST(CertifiedMotionCheck, MinimumClearanceIsTheMarginTheCheckDemands) {
  // A shoulder-pan swing past a particle 12 cm beyond the TCP. With a margin a little below the
  // motion's sampled clearance (every pair) it is accepted; with one above the start's distance from the
  // particle it is rejected (the start is measured exactly), although nothing ever touches. (Above the start's
  // closest self pair alone it would not be: self pairs keep at most 1 mm, collision_model.h.)
  Scene scene = thesisScene("thesis_free.yaml");
  const Eigen::Vector3d tcp = arcplan::robot::tipPose(arcplan::robot::ur10e(), kSolutionA).translation();
  scene.obstacles.push_back(particleAt(tcp + 0.12 * Eigen::Vector3d(tcp.x(), tcp.y(), 0.0).normalized()));
  const auto model = makeCollisionModel(scene);
  CollisionData data(*model);
  VectorXd from = kSolutionA, to = kSolutionA;
  from[0] -= 0.3;
  to[0] += 0.3;
  const double clearance = sampledClearance(*model, data, from, to);
  ASSERT_GT(clearance, 0.01);
  ASSERT_FALSE(firstCollision(*model, data, from, to));
  MotionCheckOptions options;
  // Between samples 1e-3 rad apart no point moves more than 1 mm here (the arm reaches < 1 m).
  options.minimumClearance = clearance - 0.002;
  EXPECT_TRUE(isMotionCollisionFree(*model, data, from, to, nullptr, options));
  options.minimumClearance = distance(*model, data, from).obstacleDistance + 0.001;
  EXPECT_FALSE(isMotionCollisionFree(*model, data, from, to, nullptr, options));
  double lastValid = -1.0;
  EXPECT_FALSE(isMotionCollisionFree(*model, data, from, to, &lastValid, options));
  EXPECT_EQ(lastValid, 0.0);
}

TEST(MotionBounds, NoVertexMovesFartherThanTheBound) {
  const auto model = makeCollisionModel(thesisScene("thesis_free.yaml"));
  const auto& robot = model->robot();
  const auto vertices = linkVertices(*model);
  const int bodies = static_cast<int>(vertices.size());
  arcplan::robot::KinematicsData from(robot), to(robot);
  std::mt19937_64 random(13);
  std::vector<double> tightest(bodies, 0.0);  // per link, the largest measured displacement / bound
  for (int trial = 0; trial < 300; ++trial) {
    VectorXd qa(6), dq = VectorXd::Zero(6);
    for (int j = 0; j < 6; ++j) {
      const auto& limits = robot.joints()[j].limits;
      qa[j] = std::uniform_real_distribution<double>(limits.lower, limits.upper)(random);
    }
    switch (trial % 3) {
      case 0:
        dq[static_cast<int>(random() % 6)] = std::uniform_real_distribution<double>(-0.05, 0.05)(random);
        break;
      case 1:
        for (int j = 0; j < 6; ++j) dq[j] = std::uniform_real_distribution<double>(-0.02, 0.02)(random);
        break;
      default:
        for (int j = 0; j < 6; ++j) dq[j] = std::uniform_real_distribution<double>(-1.0, 1.0)(random);
    }
    const VectorXd qb = qa + dq;
    arcplan::robot::forwardKinematics(robot, qa, from);
    arcplan::robot::forwardKinematics(robot, qb, to);
    for (int body = 0; body < bodies; ++body) {
      const int link = robot.linkIndex(model->linkNames()[body]);
      const double bound = motionBound(*model, body, qa, qb);
      for (const auto& v : vertices[body]) {
        const double moved = (to.linkPoses[link] * v - from.linkPoses[link] * v).norm();
        ASSERT_LE(moved, bound + 1e-12) << model->linkNames()[body] << " trial " << trial;
        if (bound > 0.0) tightest[body] = std::max(tightest[body], moved / bound);
      }
      // Against every other link: in the frame of the two links' nearest common ancestor, the points
      // of both together move no farther than the relative bound (which bounds how much their
      // distance can change).
      for (int other = 0; other < bodies; ++other) {
        const int otherLink = robot.linkIndex(model->linkNames()[other]);
        const int ancestor = commonAncestor(robot, link, otherLink);
        double moved = 0.0;
        for (const auto& [b, l] : {std::pair{body, link}, std::pair{other, otherLink}}) {
          const Eigen::Isometry3d inFrom = from.linkPoses[ancestor].inverse() * from.linkPoses[l];
          const Eigen::Isometry3d inTo = to.linkPoses[ancestor].inverse() * to.linkPoses[l];
          double farthest = 0.0;
          for (const auto& v : vertices[b]) farthest = std::max(farthest, (inTo * v - inFrom * v).norm());
          moved += farthest;
        }
        const double relativeBound = relativeMotionBound(*model, body, other, qa, qb);
        ASSERT_LE(moved, relativeBound + 1e-12)
            << model->linkNames()[body] << " and " << model->linkNames()[other] << " trial " << trial;
        EXPECT_EQ(relativeBound, relativeMotionBound(*model, other, body, qa, qb));
      }
    }
    EXPECT_EQ(motionBound(*model, 0, qa, qb), 0.0) << "the base link never moves";
  }
  // The bounds are not vacuous: for every moving link some vertex comes close to its bound (a link
  // turning about its own joint's axis, where the bound is that axis' farthest vertex).
  for (int body = 1; body < bodies; ++body) EXPECT_GT(tightest[body], 0.9) << model->linkNames()[body];
}

TEST(MotionBounds, ReachOfTheBaseJointIsTheArmsHorizontalExtent) {
  // A pure shoulder-pan rotation moves a point by at most its distance from the base axis times the
  // angle. Outstretched along x (shoulder lift -pi/2 points the upper arm up, so use 0), the flange
  // is about upper arm + forearm + wrist offsets away: the bound must be at least the measured
  // distance of the farthest vertex and at most the chain's total length.
  const auto model = makeCollisionModel(thesisScene("thesis_free.yaml"));
  const auto& robot = model->robot();
  const auto vertices = linkVertices(*model);
  const int flange = static_cast<int>(vertices.size()) - 1;
  VectorXd stretched = VectorXd::Zero(6), turned = VectorXd::Zero(6);
  turned[0] = 1.0;
  arcplan::robot::KinematicsData data(robot);
  arcplan::robot::forwardKinematics(robot, stretched, data);
  double farthest = 0.0;
  for (const auto& v : vertices[flange]) {
    farthest = std::max(farthest, (data.linkPoses[robot.linkIndex(model->linkNames()[flange])] * v).head<2>().norm());
  }
  const double bound = motionBound(*model, flange, stretched, turned);
  EXPECT_GE(bound, farthest);
  // Upper arm 0.6127 + forearm 0.5716 + wrist offsets (0.1742, 0.1199, 0.1166) + flange size < 1.75 m.
  EXPECT_LT(bound, 1.75);
  EXPECT_GT(farthest, 1.2);  // the configuration really is outstretched
}

TEST(CertifiedMotionCheck, RrtConnectPathsPassTheFineCheck) {
  ompl::RNG::setSeed(11);  // effective when the test runs in a process of its own (ctest)
  for (const char* name : {"thesis_free.yaml", "thesis_obstacle.yaml"}) {
    const auto model = makeCollisionModel(thesisScene(name));
    const auto si = makeSpaceInformation(model);
    const auto* validator = dynamic_cast<const JointMotionValidator*>(si->getMotionValidator().get());
    ASSERT_NE(validator, nullptr);
    EXPECT_EQ(validator->options().method, MotionCheck::Certified);
    ompl::geometric::SimpleSetup setup(si);
    ob::ScopedState<> start(si), goal(si);
    for (int j = 0; j < 6; ++j) {
      start[j] = kSolutionA[j];
      goal[j] = kSolutionB[j];
    }
    setup.setStartAndGoalStates(start, goal);
    setup.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(si));
    ASSERT_EQ(setup.solve(10.0), ob::PlannerStatus::EXACT_SOLUTION) << name;
    const auto& path = setup.getSolutionPath();
    CollisionData data(*model);
    for (std::size_t k = 1; k < path.getStateCount(); ++k) {
      EXPECT_FALSE(firstCollision(*model, data, jointsOf(path.getState(k - 1), 6), jointsOf(path.getState(k), 6)))
          << name << " motion " << k;
    }
  }
}

TEST(CertifiedMotionCheck, BadOptionsAndJointsAreErrors) {
  const auto model = makeCollisionModel(thesisScene("thesis_free.yaml"));
  CollisionData data(*model);
  const auto expectError = [&](const MotionCheckOptions& options, const std::string& field) {
    try {
      isMotionCollisionFree(*model, data, kSolutionA, kSolutionB, nullptr, options);
      ADD_FAILURE() << "no error for " << field;
    } catch (const arcplan::Error& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
    EXPECT_THROW(makeSpaceInformation(model, options), arcplan::Error) << field;
  };
  MotionCheckOptions options;
  options.minimumClearance = 0.0;
  expectError(options, "minimumClearance");
  options.minimumClearance = NAN;
  expectError(options, "minimumClearance");
  options = {};
  options.maxJointStep = -0.01;
  expectError(options, "maxJointStep");
  try {
    isMotionCollisionFree(*model, data, kSolutionA, VectorXd::Zero(5));
    ADD_FAILURE() << "no error for 5 joints";
  } catch (const arcplan::Error& e) {
    EXPECT_NE(std::string(e.what()).find("expected 6 joint values"), std::string::npos) << e.what();
  }
  VectorXd notANumber = kSolutionB;
  notANumber[2] = NAN;
  EXPECT_THROW(isMotionCollisionFree(*model, data, kSolutionA, notANumber), arcplan::Error);
  EXPECT_THROW(motionBound(*model, 99, kSolutionA, kSolutionB), arcplan::Error);
}

}  // namespace
