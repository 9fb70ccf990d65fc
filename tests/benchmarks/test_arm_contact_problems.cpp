// The generated families where the arm, not the tool, is blocked (issue 23): forearm-beam, lintel-gate,
// tilted-tool. Each property that defines a family is measured here again by other means than the
// generator's: the straight TCP line's distance to every body with FCL (a capsule of zero radius along
// the line; the generator samples points), and the arm along the line by this test's own IK walk and
// collision queries.
#include <cmath>
#include <map>
#include <set>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/distance.h>
#include <gtest/gtest.h>

#include "arcplan/benchmarks/generated_problems.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_inverse_kinematics.h"
#include "support/joint_states.h"

namespace arcplan::benchmarks {
namespace {

constexpr int kPerFamily = 10;
const std::vector<std::string> kFamilies{"forearm-beam", "lintel-gate", "tilted-tool"};

GeneratorSettings armContactSettings(std::uint64_t seed, int perFamily) {
  GeneratorSettings settings;
  settings.seed = seed;
  settings.lineObstacles = settings.pillars = settings.shelves = 0;
  settings.forearmBeams = settings.lintelGates = settings.tiltedTools = perFamily;
  return settings;
}

const std::vector<Problem>& armContactProblems() {
  static const auto problems = generateProblems(armContactSettings(11, kPerFamily));
  return problems;
}

// FCL's shape for an obstacle of the generated scenes (primitives only).
std::shared_ptr<fcl::CollisionGeometryd> fclShape(const collision::Obstacle& body) {
  switch (body.shape) {
    case collision::Obstacle::Shape::Sphere:
      return std::make_shared<fcl::Sphered>(body.radius);
    case collision::Obstacle::Shape::Box:
      return std::make_shared<fcl::Boxd>(body.size);
    case collision::Obstacle::Shape::Cylinder:
      return std::make_shared<fcl::Cylinderd>(body.radius, body.length);
    default:
      ADD_FAILURE() << "unexpected mesh obstacle " << body.name;
      return nullptr;
  }
}

// FCL distance between the segment a-b (a capsule of 1 nm radius) and the body.
double segmentToBody(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const collision::Obstacle& body) {
  const fcl::Capsuled segment(1e-9, (b - a).norm());
  fcl::Transform3d segmentPose = fcl::Transform3d::Identity();
  segmentPose.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), b - a).toRotationMatrix();
  segmentPose.translation() = 0.5 * (a + b);
  const auto shape = fclShape(body);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::DistanceResultd result;
  return fcl::distance(&segment, segmentPose, shape.get(), fcl::Transform3d(body.pose.matrix()), request, result);
}

struct LineWalk {
  std::map<std::string, std::set<std::string>> contacts;  // obstacle -> links touching it
  robot::Vector6 end;                                     // the configuration the walk ends in
};

// Follows the straight TCP line from the start's pose to the goal's, tool orientation held, with this
// test's own IK continuation (5 mm steps, as the generator defines the family) and records every
// robot–obstacle contact.
LineWalk walkTheLine(const Problem& problem) {
  const auto& model = robot::ur10e();
  const robot::UrInverseKinematics ik(model);
  const auto& query = problem.scene.queries.front();
  Eigen::Isometry3d pose = robot::tipPose(model, *query.start.joints);
  const Eigen::Vector3d a = pose.translation(), b = robot::tipPose(model, *query.goal.joints).translation();
  std::set<std::string> obstacles;
  for (const auto& body : problem.scene.obstacles) obstacles.insert(body.name);
  const auto collisionModel = collision::makeCollisionModel(problem.scene);
  collision::CollisionData data(*collisionModel);
  LineWalk walk;
  robot::Vector6 q = *query.start.joints;
  const int steps = static_cast<int>(std::ceil((b - a).norm() / 0.005));
  for (int k = 0; k <= steps; ++k) {
    pose.translation() = a + (b - a) * (static_cast<double>(k) / steps);
    const auto next = ik.solveNearest(pose, q);
    if (!next) {
      ADD_FAILURE() << "no IK solution at step " << k;
      break;
    }
    q = *next;
    for (const auto& [first, second] : collision::collide(*collisionModel, data, q).collisions) {
      if (obstacles.count(second) > 0) walk.contacts[second].insert(first);
      if (obstacles.count(first) > 0) walk.contacts[first].insert(second);
    }
  }
  walk.end = q;
  return walk;
}

bool touchedByOneOf(const LineWalk& walk, const std::string& body, const std::set<std::string>& links) {
  const auto found = walk.contacts.find(body);
  if (found == walk.contacts.end()) return false;
  for (const auto& link : links) {
    if (found->second.count(link) > 0) return true;
  }
  return false;
}

bool toolTouchesSomething(const LineWalk& walk) {
  for (const auto& [body, links] : walk.contacts) {
    if (links.count("wrist_3_link") > 0) return true;
  }
  return false;
}

TEST(ArmContactProblems, TenOrMoreOfEachFamilyWithValidEnds) {
  std::map<std::string, int> kinds;
  const auto& model = robot::ur10e();
  for (const auto& problem : armContactProblems()) {
    SCOPED_TRACE(problem.name);
    ++kinds[problem.kind];
    const auto collisionModel = collision::makeCollisionModel(problem.scene);
    collision::CollisionData data(*collisionModel);
    const auto& query = problem.scene.queries.front();
    for (const auto& q : {*query.start.joints, *query.goal.joints}) {
      arcplan::testing::expectWithinJointLimits(model, q);
      EXPECT_GE(collision::distance(*collisionModel, data, q).minimum(), 0.01);  // the suites' clearance
    }
  }
  for (const auto& family : kFamilies) EXPECT_EQ(kinds[family], kPerFamily) << family;
  EXPECT_EQ(armContactProblems().size(), kFamilies.size() * kPerFamily);
}

TEST(ArmContactProblems, TheStraightTcpLineKeepsOneCentimetreFromEveryBody) {
  const auto& model = robot::ur10e();
  for (const auto& problem : armContactProblems()) {
    SCOPED_TRACE(problem.name);
    const auto& query = problem.scene.queries.front();
    const Eigen::Vector3d a = robot::tipPose(model, *query.start.joints).translation();
    const Eigen::Vector3d b = robot::tipPose(model, *query.goal.joints).translation();
    ASSERT_GE(problem.scene.obstacles.size(), 2u);
    for (std::size_t i = 1; i < problem.scene.obstacles.size(); ++i) {  // the table is below the line
      EXPECT_GE(segmentToBody(a, b, problem.scene.obstacles[i]), 0.01 - 1e-6) << problem.scene.obstacles[i].name;
    }
  }
}

TEST(ArmContactProblems, TheArmFollowingTheLineMeetsTheBlockingBody) {
  for (const auto& problem : armContactProblems()) {
    SCOPED_TRACE(problem.name);
    const auto walk = walkTheLine(problem);
    // The walk is the start's IK branch all the way: it ends in the goal.
    EXPECT_LT((walk.end - *problem.scene.queries.front().goal.joints).norm(), 1e-6);
    if (problem.kind == "forearm-beam") {
      EXPECT_TRUE(touchedByOneOf(walk, "beam", {"upper_arm_link", "forearm_link"}));
      EXPECT_FALSE(toolTouchesSomething(walk)) << "the tool must not be what is blocked";
    } else if (problem.kind == "lintel-gate") {
      EXPECT_TRUE(touchedByOneOf(walk, "lintel", {"forearm_link", "wrist_1_link", "wrist_2_link"}));
      EXPECT_FALSE(toolTouchesSomething(walk)) << "the tool must not be what is blocked";
    } else {
      EXPECT_TRUE(touchedByOneOf(walk, "obstacle", {"wrist_1_link", "wrist_2_link", "wrist_3_link"}));
    }
  }
}

TEST(ArmContactProblems, BodiesAreTheBeamsGatesAndToolTiltsTheFamiliesPromise) {
  const auto& model = robot::ur10e();
  for (const auto& problem : armContactProblems()) {
    SCOPED_TRACE(problem.name);
    const auto& query = problem.scene.queries.front();
    const auto start = robot::tipPose(model, *query.start.joints), goal = robot::tipPose(model, *query.goal.joints);
    const auto& obstacles = problem.scene.obstacles;
    const Eigen::Vector3d toolAxis = start.linear().col(2);
    const double tilt = std::acos(std::clamp(-toolAxis.z(), -1.0, 1.0));  // from straight down
    EXPECT_LT(robot::rotationDistance(start.linear(), goal.linear()), 1e-9) << "the tool orientation is held";
    if (problem.kind == "forearm-beam") {
      ASSERT_EQ(obstacles.size(), 2u);
      EXPECT_EQ(obstacles[1].shape, collision::Obstacle::Shape::Box);
      EXPECT_NEAR((obstacles[1].pose.linear().col(2) - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-12);  // level
      EXPECT_GE(obstacles[1].size.x(), 0.5);
      EXPECT_LE(obstacles[1].size.x(), 1.2);
      EXPECT_LT(tilt, 1e-6);
    } else if (problem.kind == "lintel-gate") {
      ASSERT_EQ(obstacles.size(), 4u);  // table, two posts, lintel
      const auto& lintel = obstacles[3];
      const double bottom = lintel.pose.translation().z() - 0.5 * lintel.size.z();
      for (const auto& post : {obstacles[1], obstacles[2]}) {
        EXPECT_NEAR(post.pose.translation().z() - 0.5 * post.size.z(), 0.0, 1e-12);     // on the table
        EXPECT_NEAR(post.pose.translation().z() + 0.5 * post.size.z(), bottom, 1e-12);  // holds the lintel
      }
      EXPECT_GT(bottom, std::min(start.translation().z(), goal.translation().z()) + 0.05 - 1e-12);
      EXPECT_LT(bottom, std::max(start.translation().z(), goal.translation().z()) + 0.35 + 1e-12);
      EXPECT_LT(tilt, 1e-6);
    } else {
      ASSERT_EQ(obstacles.size(), 2u);
      EXPECT_GE(tilt, M_PI / 6.0 - 1e-9);  // 30 to 70 degrees off vertical
      EXPECT_LE(tilt, 7.0 * M_PI / 18.0 + 1e-9);
    }
  }
}

TEST(ArmContactProblems, SameSeedSameProblemsWhateverTheCountAsked) {
  // Each problem has its own random stream: asking for 2 per family gives the first 2 of the 10.
  const auto few = generateProblems(armContactSettings(11, 2));
  ASSERT_EQ(few.size(), 6u);
  for (std::size_t f = 0; f < kFamilies.size(); ++f) {
    for (std::size_t i = 0; i < 2; ++i) {
      const auto& mine = few[f * 2 + i];
      const auto& full = armContactProblems()[f * kPerFamily + i];
      EXPECT_EQ(mine.name, full.name);
      EXPECT_EQ(collision::sceneToYaml(mine.scene), collision::sceneToYaml(full.scene));
    }
  }
  const auto other = generateProblems(armContactSettings(12, 1));
  for (std::size_t f = 0; f < kFamilies.size(); ++f) {
    EXPECT_NE(collision::sceneToYaml(other[f].scene),
              collision::sceneToYaml(armContactProblems()[f * kPerFamily].scene));
  }
}

}  // namespace
}  // namespace arcplan::benchmarks
