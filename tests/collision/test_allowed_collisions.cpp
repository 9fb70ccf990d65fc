// The allowed-collision matrix: adjacency from the URDF chain, the recorded UR10e file, and a fresh
// sample (other seed than the generator's) confirming that the recorded "never" pairs never touch.
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "arcplan/collision/allowed_collisions.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/common/error.h"
#include "support/command.h"
#include "support/joint_states.h"

namespace {

using namespace arcplan::collision;
using Pairs = std::vector<std::pair<std::string, std::string>>;

TEST(AllowedCollisions, PairsAreUnordered) {
  AllowedCollisionMatrix allowed;
  allowed.allow("b", "a");
  EXPECT_TRUE(allowed.isAllowed("a", "b"));
  EXPECT_TRUE(allowed.isAllowed("b", "a"));
  EXPECT_FALSE(allowed.isAllowed("a", "c"));
  allowed.allow("a", "b");
  EXPECT_EQ(allowed.size(), 1u);
  EXPECT_EQ(allowed.pairs(), (Pairs{{"a", "b"}}));
}

TEST(AllowedCollisions, AdjacentLinksOfTheUr10eChain) {
  // base_link has no geometry, so base_link_inertia starts the chain; tool frames have none either.
  const Pairs expected{{"base_link_inertia", "shoulder_link"}, {"forearm_link", "upper_arm_link"},
                       {"forearm_link", "wrist_1_link"},       {"shoulder_link", "upper_arm_link"},
                       {"wrist_1_link", "wrist_2_link"},       {"wrist_2_link", "wrist_3_link"}};
  EXPECT_EQ(adjacentLinkPairs(arcplan::robot::ur10e()).pairs(), expected);
}

TEST(AllowedCollisions, RecordedFileHoldsAdjacentAndNeverPairs) {
  const AllowedCollisionMatrix recorded = loadAllowedCollisions(ur10eAllowedCollisionsPath());
  const auto& robot = arcplan::robot::ur10e();
  for (const auto& pair : adjacentLinkPairs(robot).pairs()) EXPECT_TRUE(recorded.isAllowed(pair.first, pair.second));
  // Pairs that plainly can collide stay checked: the wrist can reach the upper arm and the base.
  EXPECT_FALSE(recorded.isAllowed("upper_arm_link", "wrist_3_link"));
  EXPECT_FALSE(recorded.isAllowed("base_link_inertia", "wrist_3_link"));
  EXPECT_FALSE(recorded.isAllowed("shoulder_link", "forearm_link"));
  // The built-in UR10e gets the file by default, a model from another file only adjacency.
  EXPECT_EQ(defaultAllowedCollisions(robot).pairs(), recorded.pairs());
}

TEST(AllowedCollisions, RecordedNeverPairsDoNotCollideInFreshSamples) {
  const auto robot = std::make_shared<const arcplan::robot::RobotModel>(arcplan::robot::ur10e());
  const AllowedCollisionMatrix adjacent = adjacentLinkPairs(*robot);
  const AllowedCollisionMatrix recorded = loadAllowedCollisions(ur10eAllowedCollisionsPath());
  Pairs never;
  for (const auto& pair : recorded.pairs()) {
    if (!adjacent.isAllowed(pair.first, pair.second)) never.push_back(pair);
  }
  ASSERT_FALSE(never.empty());
  // Only adjacency allowed: collide() reports every other colliding pair.
  const CollisionModel model(robot, Scene{}, adjacent);
  CollisionData data(model);
  std::mt19937_64 random(2024);
  int collidingStates = 0;
  for (int sample = 0; sample < 3000; ++sample) {
    const Eigen::VectorXd q = arcplan::testing::randomJointState(*robot, random);
    const auto report = collide(model, data, q);
    collidingStates += report.valid ? 0 : 1;
    for (const auto& pair : report.collisions) {
      EXPECT_FALSE(recorded.isAllowed(pair.first, pair.second)) << pair.first << " - " << pair.second << " collided";
    }
  }
  EXPECT_GT(collidingStates, 100);  // the sample does reach self-collisions
}

TEST(AllowedCollisions, BadFileSaysWhere) {
  const auto dir = arcplan::testing::freshTempDirectory("acm_bad");
  std::ofstream(dir / "acm.yaml") << "allowed_collisions:\n  - {links: [a]}\n";
  try {
    loadAllowedCollisions(dir / "acm.yaml");
    FAIL() << "no error";
  } catch (const arcplan::Error& e) {
    EXPECT_NE(std::string(e.what()).find("acm.yaml:2:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("allowed_collisions[0]: expected a pair [link, link]"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(loadAllowedCollisions(dir / "missing.yaml"), arcplan::Error);
}

}  // namespace
