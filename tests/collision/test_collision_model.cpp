// Collision and distance queries on arcplan's UR10e: the thesis configurations, the table, self
// collision, obstacles at known places, analytic distances, and agreement between the queries and
// between the narrow-phase variants.
#include <cmath>
#include <fstream>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/ur_inverse_kinematics.h"
#include "support/command.h"
#include "support/joint_states.h"
#include "support/obstacles.h"

namespace {

using namespace arcplan::collision;
using arcplan::robot::Vector6;

Scene thesisScene(const char* name = "thesis_obstacle.yaml") {
  return loadScene(arcplan::dataDirectory() / "scenes" / name);
}

// The issue's elbow-up, wrist-down IK solution of pose A.
const Vector6 kSolutionA = (Vector6() << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098).finished();

bool hasPair(const CollisionReport& report, const std::string& a, const std::string& b) {
  for (const auto& [first, second] : report.collisions) {
    if ((first == a && second == b) || (first == b && second == a)) return true;
  }
  return false;
}

std::vector<Eigen::VectorXd> randomConfigurations(const arcplan::robot::RobotModel& robot, int count, unsigned seed) {
  std::mt19937_64 random(seed);
  std::vector<Eigen::VectorXd> result;
  for (int i = 0; i < count; ++i) result.push_back(arcplan::testing::randomJointState(robot, random));
  return result;
}

TEST(CollisionModel, ThesisSolutionOfPoseAIsValid) {
  const auto model = makeCollisionModel(thesisScene());
  CollisionData data(*model);
  EXPECT_TRUE(isCollisionFree(*model, data, kSolutionA));
  const auto report = collide(*model, data, kSolutionA);
  EXPECT_TRUE(report.valid);
  EXPECT_TRUE(report.collisions.empty());
  // tool0 is 0.25 m above the table, pointing down; the particle is 0.09 m higher and 0.3 m away.
  const auto distances = distance(*model, data, kSolutionA);
  EXPECT_GT(distances.obstacleDistance, 0.05);
  EXPECT_LT(distances.obstacleDistance, 0.25);
  EXPECT_GT(distances.selfDistance, 0.0);
}

TEST(CollisionModel, ElbowDownSolutionsOfPoseAHitTheTable) {
  const auto model = makeCollisionModel(thesisScene());
  CollisionData data(*model);
  const auto& robot = model->robot();
  const arcplan::robot::UrInverseKinematics ik(robot);
  const auto target = arcplan::robot::poseFromXyzRpy({0.4, -0.4, 0.25, 0, -M_PI, M_PI / 2});
  arcplan::robot::KinematicsData kinematics(robot);
  int elbowDown = 0;
  for (const auto& q : ik.solveBranches(target)) {
    arcplan::robot::forwardKinematics(robot, q, kinematics);
    const double elbowHeight = kinematics.linkPoses[robot.linkIndex("forearm_link")].translation().z();
    if (elbowHeight > 0.05) continue;  // facts §6: four branches put the elbow at z <= 0.02
    ++elbowDown;
    const auto report = collide(*model, data, q);
    EXPECT_FALSE(report.valid) << q.transpose();
    bool table = false;
    for (const auto& pair : report.collisions) table |= pair.second == "table";
    EXPECT_TRUE(table) << "elbow at z = " << elbowHeight << " but no link touches the table";
  }
  EXPECT_EQ(elbowDown, 4);
}

TEST(CollisionModel, FoldedArmHitsItself) {
  // Elbow folded to its limit: the forearm lies back along the upper arm, so the wrist-1 housing
  // (around an axis 0.6127 - 0.57155 = 0.041 m from the shoulder-lift axis) sits inside the
  // upper arm's shoulder-lift housing (radius 0.0767 around that axis).
  const auto model = makeCollisionModel(thesisScene("thesis_free.yaml"));
  CollisionData data(*model);
  Vector6 folded;
  folded << 0.0, -M_PI / 2, M_PI, 0.0, M_PI / 2, 0.0;
  const auto report = collide(*model, data, folded);
  EXPECT_FALSE(report.valid);
  EXPECT_TRUE(hasPair(report, "upper_arm_link", "wrist_1_link"));
  for (const auto& [first, second] : report.collisions) EXPECT_NE(second, "table") << first;
  EXPECT_EQ(distance(*model, data, folded).selfDistance, 0.0);
}

TEST(CollisionModel, ParticleAtTool0Collides) {
  Scene scene = thesisScene("thesis_free.yaml");
  const auto& robot = arcplan::robot::ur10e();
  const Eigen::Vector3d tool0 = arcplan::robot::tipPose(robot, kSolutionA).translation();
  scene.obstacles.push_back(arcplan::testing::sphere("particle", tool0, 0.01));
  const auto model = makeCollisionModel(scene);
  CollisionData data(*model);
  EXPECT_FALSE(isCollisionFree(*model, data, kSolutionA));
  const auto report = collide(*model, data, kSolutionA);
  EXPECT_TRUE(hasPair(report, "wrist_3_link", "particle"));
  const auto distances = distance(*model, data, kSolutionA);
  EXPECT_EQ(distances.obstacleDistance, 0.0);
  EXPECT_EQ(distances.obstaclePair.second, "particle");
}

TEST(CollisionModel, ParticleInsideALinkCollidesAlthoughNoSurfaceIsHit) {
  // A 1 cm particle on the upper-arm tube axis, 0.3 m from the shoulder: entirely inside the tube
  // (radius 0.0553), touching none of its triangles.
  Scene scene = thesisScene("thesis_free.yaml");
  const auto& robot = arcplan::robot::ur10e();
  arcplan::robot::KinematicsData kinematics(robot);
  arcplan::robot::forwardKinematics(robot, kSolutionA, kinematics);
  const Eigen::Vector3d inside =
      kinematics.linkPoses[robot.linkIndex("upper_arm_link")] * Eigen::Vector3d(-0.3, 0, 0.1762);
  scene.obstacles.push_back(arcplan::testing::sphere("particle", inside, 0.01));
  for (bool convex : {true, false}) {
    CollisionModelOptions options;
    options.convexCollision = options.convexDistance = convex;
    const auto model = makeCollisionModel(scene, options);
    CollisionData data(*model);
    const auto report = collide(*model, data, kSolutionA);
    EXPECT_TRUE(hasPair(report, "upper_arm_link", "particle")) << "convex " << convex;
    EXPECT_EQ(distance(*model, data, kSolutionA).obstacleDistance, 0.0) << "convex " << convex;
  }
}

TEST(CollisionModel, DistanceToTheFlangeFaceIsExact) {
  // tool0 lies on the flange face (wrist_3_link's end disc at z = 0), z pointing out of it. A ball
  // of radius 0.01 on that axis 0.1 m out is 0.09 m from the flat face and farther from anything else.
  Scene scene = thesisScene("thesis_free.yaml");
  const auto& robot = arcplan::robot::ur10e();
  const Eigen::Isometry3d tool0 = arcplan::robot::tipPose(robot, kSolutionA);
  scene.obstacles.push_back(arcplan::testing::sphere("ball", tool0 * Eigen::Vector3d(0, 0, 0.1), 0.01));
  AllowedCollisionMatrix allowed = defaultAllowedCollisions(robot);
  for (const auto& link : {"base_link_inertia", "shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link",
                           "wrist_2_link", "wrist_3_link"}) {
    allowed.allow(link, "table");  // only the ball is measured
  }
  for (bool convex : {true, false}) {
    CollisionModelOptions options;
    options.convexDistance = convex;
    const CollisionModel model(std::make_shared<const arcplan::robot::RobotModel>(robot), scene, allowed, options);
    CollisionData data(model);
    const auto distances = distance(model, data, kSolutionA);
    EXPECT_NEAR(distances.obstacleDistance, 0.09, 1e-6) << "convex " << convex;
    EXPECT_EQ(distances.obstaclePair, NamePair("wrist_3_link", "ball"));
  }
}

// A one-joint robot whose link is a URDF cylinder (radius 0.05, length 0.4, along the link z),
// pivoting about x at (0, 0, 0.5).
std::shared_ptr<const arcplan::robot::RobotModel> pendulum(const std::filesystem::path& dir) {
  const auto urdf = dir / "pendulum.urdf";
  std::ofstream(urdf) << R"(<robot name="pendulum">
  <link name="base_link"/>
  <link name="rod"><collision><origin xyz="0 0 0" rpy="0 0 0"/><geometry><cylinder radius="0.05" length="0.4"/></geometry></collision></link>
  <link name="tip"/>
  <joint name="swing" type="revolute"><parent link="base_link"/><child link="rod"/><origin xyz="0 0 0.5" rpy="0 0 0"/>
    <axis xyz="1 0 0"/><limit lower="-3" upper="3" velocity="1" effort="1"/></joint>
  <joint name="rod_tip" type="fixed"><parent link="rod"/><child link="tip"/><origin xyz="0 0 0.2" rpy="0 0 0"/></joint>
</robot>)";
  return std::make_shared<const arcplan::robot::RobotModel>(
      arcplan::robot::loadRobotModel(urdf, {"base_link", "tip", std::nullopt}));
}

// Distance from a point to a solid cylinder given the point's axial coordinate t (from the centre)
// and its distance rho from the axis.
double pointToCylinder(double t, double rho, double radius, double halfLength) {
  const double axialGap = std::max(std::abs(t) - halfLength, 0.0), radialGap = std::max(rho - radius, 0.0);
  return std::hypot(axialGap, radialGap);
}

TEST(CollisionModel, ClearanceMatchesSphereToCylinderByHand) {
  const auto dir = arcplan::testing::freshTempDirectory("pendulum");
  const auto robot = pendulum(dir);
  const Eigen::Vector3d pivot(0, 0, 0.5);
  // One ball beside the pivot (its distance to the axis never changes), one above it.
  const Eigen::Vector3d side = pivot + Eigen::Vector3d(0.3, 0, 0), above = pivot + Eigen::Vector3d(0, 0, 0.5);
  for (const auto& centre : {side, above}) {
    Scene scene;
    scene.obstacles.push_back(arcplan::testing::sphere("ball", centre, 0.05));
    for (bool convex : {true, false}) {
      CollisionModelOptions options;
      options.convexDistance = convex;
      const CollisionModel model(robot, scene, AllowedCollisionMatrix{}, options);
      CollisionData data(model);
      for (double angle : {0.0, 0.1, 0.3, 0.7, 1.2, 2.0}) {
        const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, angle);
        // Rotation about x by `angle` turns the rod axis to (0, -sin, cos).
        const Eigen::Vector3d axis(0, -std::sin(angle), std::cos(angle));
        const Eigen::Vector3d offset = centre - pivot;
        const double t = offset.dot(axis), rho = (offset - t * axis).norm();
        const double expected = std::max(pointToCylinder(t, rho, 0.05, 0.2) - 0.05, 0.0);
        const auto distances = distance(model, data, q);
        EXPECT_NEAR(distances.obstacleDistance, expected, 2e-6) << "angle " << angle << " convex " << convex;
        EXPECT_EQ(collide(model, data, q).valid, expected > 0.0) << "angle " << angle;
        EXPECT_TRUE(std::isinf(distances.selfDistance));  // one link: no self pair
      }
    }
  }
}

TEST(CollisionModel, AllowedPairsAreNotReported) {
  Scene scene = thesisScene("thesis_free.yaml");
  scene.obstacles[0].pose.translation().z() += 0.002;  // table top 2 mm into the base
  const auto robot = std::make_shared<const arcplan::robot::RobotModel>(arcplan::robot::ur10e());
  AllowedCollisionMatrix withoutTable = defaultAllowedCollisions(*robot);
  const CollisionModel strict(robot, scene, withoutTable);
  CollisionData strictData(strict);
  const auto report = collide(strict, strictData, kSolutionA);
  EXPECT_FALSE(report.valid);
  EXPECT_TRUE(hasPair(report, "base_link_inertia", "table"));
  EXPECT_EQ(report.collisions.size(), 1u);

  AllowedCollisionMatrix withTable = withoutTable;
  withTable.allow("table", "base_link_inertia");  // either order
  const CollisionModel relaxed(robot, scene, withTable);
  CollisionData relaxedData(relaxed);
  EXPECT_TRUE(isCollisionFree(relaxed, relaxedData, kSolutionA));

  // A folded arm collides with itself only through non-allowed pairs; allowing them all hides it.
  Vector6 folded;
  folded << 0.0, -M_PI / 2, M_PI, 0.0, M_PI / 2, 0.0;
  AllowedCollisionMatrix everything = withTable;
  for (const auto& a : strict.linkNames()) {
    for (const auto& b : strict.linkNames()) everything.allow(a, b);
  }
  const CollisionModel permissive(robot, scene, everything);
  CollisionData permissiveData(permissive);
  EXPECT_FALSE(isCollisionFree(relaxed, relaxedData, folded));
  EXPECT_TRUE(isCollisionFree(permissive, permissiveData, folded));
  EXPECT_EQ(permissive.selfPairCount(), 0u);
}

TEST(CollisionModel, RejectsUnknownNamesInTheAllowedPairs) {
  const auto robot = std::make_shared<const arcplan::robot::RobotModel>(arcplan::robot::ur10e());
  AllowedCollisionMatrix allowed;
  allowed.allow("wrist_3_link", "bucket");
  try {
    CollisionModel model(robot, thesisScene(), allowed);
    FAIL() << "no error";
  } catch (const arcplan::Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown link or obstacle 'bucket'"), std::string::npos) << e.what();
  }
}

TEST(CollisionModel, DistanceAndCollideAgreeOnRandomConfigurations) {
  const auto model = makeCollisionModel(thesisScene());
  CollisionData data(*model);
  int invalid = 0;
  for (const auto& q : randomConfigurations(model->robot(), 400, 5)) {
    const auto report = collide(*model, data, q);
    const auto distances = distance(*model, data, q);
    EXPECT_EQ(report.valid, distances.minimum() > 0.0) << q.transpose();
    EXPECT_EQ(report.valid, isCollisionFree(*model, data, q)) << q.transpose();
    if (!report.valid) {
      ++invalid;
      // The zero distance names one of the colliding pairs.
      const NamePair& zeroPair = distances.obstacleDistance == 0.0 ? distances.obstaclePair : distances.selfPair;
      EXPECT_TRUE(hasPair(report, zeroPair.first, zeroPair.second)) << zeroPair.first << " " << zeroPair.second;
    }
  }
  // Uniform samples of a table-mounted arm: a good share collide, a good share do not.
  EXPECT_GT(invalid, 40);
  EXPECT_LT(invalid, 360);
}

TEST(CollisionModel, NarrowPhaseVariantsAgree) {
  const Scene scene = thesisScene();
  const auto reference = makeCollisionModel(scene);
  CollisionData referenceData(*reference);
  struct Variant {
    BoundingVolume collisionBv, distanceBv;
    bool convex, broadPhase;
  };
  const std::vector<Variant> variants{{BoundingVolume::OBB, BoundingVolume::OBBRSS, false, true},
                                      {BoundingVolume::kIOS, BoundingVolume::kIOS, false, true},
                                      {BoundingVolume::OBBRSS, BoundingVolume::RSS, false, true},
                                      {BoundingVolume::OBB, BoundingVolume::OBBRSS, true, false},
                                      {BoundingVolume::OBB, BoundingVolume::OBBRSS, false, false}};
  const auto configurations = randomConfigurations(reference->robot(), 150, 9);
  for (const auto& variant : variants) {
    CollisionModelOptions options;
    options.collisionBoundingVolume = variant.collisionBv;
    options.distanceBoundingVolume = variant.distanceBv;
    options.convexCollision = options.convexDistance = variant.convex;
    options.broadPhase = variant.broadPhase;
    const auto model = makeCollisionModel(scene, options);
    CollisionData data(*model);
    for (const auto& q : configurations) {
      const auto expected = collide(*reference, referenceData, q);
      const auto actual = collide(*model, data, q);
      EXPECT_EQ(actual.valid, expected.valid) << toString(variant.collisionBv) << " " << q.transpose();
      EXPECT_EQ(std::set<NamePair>(actual.collisions.begin(), actual.collisions.end()),
                std::set<NamePair>(expected.collisions.begin(), expected.collisions.end()));
      EXPECT_NEAR(distance(*model, data, q).minimum(), distance(*reference, referenceData, q).minimum(), 2e-6)
          << toString(variant.distanceBv) << " " << q.transpose();
    }
  }
}

TEST(CollisionModel, RejectsWrongJointCountAndOBBDistances) {
  const auto model = makeCollisionModel(thesisScene());
  CollisionData data(*model);
  EXPECT_THROW(isCollisionFree(*model, data, Eigen::VectorXd::Zero(5)), arcplan::Error);
  CollisionModelOptions options;
  options.distanceBoundingVolume = BoundingVolume::OBB;
  EXPECT_THROW(makeCollisionModel(thesisScene(), options), arcplan::Error);
}

}  // namespace
