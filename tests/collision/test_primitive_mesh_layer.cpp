// The containing-mesh layer (docs/collision.md, "Layers"): a primitive's circumscribed triangle mesh bounds its
// distance to a mesh part from below, within the tessellation's gap. Expected distances come from FCL's exact
// mesh-vs-primitive query (partsDistance) and from the primitives' formulas; answers of the query functions are
// compared with a model that has the layers off, on states around a grasp of MotionBenchMaker's UR5 + Robotiq 85.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/kinematics.h"
#include "containing_meshes.h"     // collision/src
#include "model_implementation.h"  // collision/src
#include "support/command.h"

namespace {

using namespace arcplan::collision;
using namespace arcplan::collision::detail;
namespace fs = std::filesystem;

fs::path problemFolder() {
  return arcplan::testing::sharedDataDirectory() / "mbm_ur5" / "problems" / "bookshelf_tall_ur5";
}

MoveItProblem graspProblem() {
  const fs::path mbm = arcplan::testing::sharedDataDirectory() / "mbm_ur5";
  return loadMoveItProblem(problemFolder() / "scene0081.yaml", problemFolder() / "request0081.yaml",
                           {mbm / "ur5.urdf", mbm / "ur5.srdf"});
}

// Distance of a point from a cylinder (axis z, centred) and a box, written out.
double cylinderDistance(const Eigen::Vector3d& p, double radius, double halfLength) {
  const double radial = std::max(p.head<2>().norm() - radius, 0.0), axial = std::max(std::abs(p.z()) - halfLength, 0.0);
  return std::hypot(radial, axial);
}

TEST(ContainingMeshes, ContainThePrimitiveWithinTheStatedGap) {
  const double r = 0.03, length = 0.14;
  const ContainingMesh cylinder = containingCylinderMesh(r, length, 32);
  EXPECT_NEAR(cylinder.largestGap, r * (1.0 / std::cos(M_PI / 32) - 1.0), 1e-15);
  const ContainingMesh sphere = containingSphereMesh(r);
  const auto checkFaces = [](const ContainingMesh& mesh, const auto& farthestInward, const auto& gapOf) {
    for (const auto& t : mesh.mesh.triangles) {
      const Eigen::Vector3d& a = mesh.mesh.vertices[t[0]];
      const Eigen::Vector3d n = (mesh.mesh.vertices[t[1]] - a).cross(mesh.mesh.vertices[t[2]] - a).normalized();
      // Outward, and the primitive's support along n (its farthest point) no farther than the face's plane.
      EXPECT_GE(n.dot(a) + 1e-12, farthestInward(n));
    }
    for (const auto& v : mesh.mesh.vertices) EXPECT_LE(gapOf(v), mesh.largestGap + 1e-12);
  };
  checkFaces(
      cylinder, [&](const Eigen::Vector3d& n) { return r * n.head<2>().norm() + length / 2 * std::abs(n.z()); },
      [&](const Eigen::Vector3d& v) { return cylinderDistance(v, r, length / 2); });
  checkFaces(
      sphere, [&](const Eigen::Vector3d&) { return r; }, [&](const Eigen::Vector3d& v) { return v.norm() - r; });
  // A sphere's mesh stays within its gap of the sphere, which is a few per cent of the radius.
  EXPECT_LT(sphere.largestGap, 0.05 * r);
}

// The largest non-convex part of a Robotiq finger tip (the 1776-triangle mesh of the profile).
int fingerTipPart(const CollisionModel& model) {
  const ModelImplementation& impl = implementationOf(model);
  int best = -1;
  for (int i = 0; i < static_cast<int>(impl.robotParts.size()); ++i) {
    const Part& part = impl.robotParts[i];
    if (model.linkNames()[part.body].find("finger_tip") == std::string::npos || part.convexGeometry) continue;
    if (best < 0 || part.hullPoints.size() > impl.robotParts[best].hullPoints.size()) best = i;
  }
  return best;
}

TEST(ContainingMeshLayer, BoundsTheExactDistanceFromBelowWithinTheGap) {
  const auto model = makeCollisionModel(graspProblem().scene);
  const int tip = fingerTipPart(*model);
  ASSERT_GE(tip, 0);
  const Part& mesh = implementationOf(*model).robotParts[tip];
  const BoundingVolume bvh = model->options().distanceBoundingVolume;
  const double r = 0.03;
  struct Case {
    Part part;
    double gap;
  };
  const Case cases[] = {{cylinderPart(r, 0.14, bvh), containingCylinderMesh(r, 0.14).largestGap},
                        {spherePart(r, bvh), containingSphereMesh(r).largestGap}};
  const Eigen::Vector3d centre = 0.5 * (mesh.capsule.start + mesh.capsule.end);
  std::mt19937 random(20261124);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int positive = 0;
  for (const Case& c : cases) {
    for (int trial = 0; trial < 300; ++trial) {
      const Eigen::Vector3d axis = Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
      Eigen::Isometry3d pose(Eigen::AngleAxisd(M_PI * unit(random), axis));
      pose.translation() =
          centre + (mesh.capsule.radius + 0.08) * Eigen::Vector3d(unit(random), unit(random), unit(random));
      const double exact = partsDistance(mesh, Eigen::Isometry3d::Identity(), c.part, pose, true, {});
      const double bound = containingMeshGap(mesh, Eigen::Isometry3d::Identity(), c.part, pose, {});
      EXPECT_EQ(bound, containingMeshGap(c.part, pose, mesh, Eigen::Isometry3d::Identity(), {}));  // either order
      EXPECT_LE(bound, exact) << "trial " << trial;
      EXPECT_GE(bound, exact - c.gap - 1e-5) << "trial " << trial;
      positive += bound > 0.0;
    }
  }
  EXPECT_GT(positive, 200);  // most poses apart: the bound is not trivially 0
  // No bound with the layer off, for a mesh part of few triangles (measured exactly at once), for a box.
  const Eigen::Isometry3d apart(Eigen::Translation3d(centre + Eigen::Vector3d(0.3, 0, 0)));
  Part few = mesh;
  few.triangleCount = kContainingMeshMinTriangles - 1;
  EXPECT_GT(containingMeshGap(mesh, Eigen::Isometry3d::Identity(), cases[0].part, apart, {}), 0.2);
  EXPECT_EQ(containingMeshGap(few, Eigen::Isometry3d::Identity(), cases[0].part, apart, {}), 0.0);
  EXPECT_EQ(containingMeshGap(mesh, Eigen::Isometry3d::Identity(), boxPart({0.06, 0.05, 0.12}), apart, {}), 0.0);
  CollisionModelOptions off;
  off.hullLayer = false;
  EXPECT_EQ(containingMeshGap(mesh, Eigen::Isometry3d::Identity(), cases[0].part, apart, off), 0.0);
}

// States around the goal of bookshelf_tall 0081 (the gripper at the can): every answer equals the layers-off one.
TEST(ContainingMeshLayer, AnswersEqualThoseWithoutTheLayersAroundAGrasp) {
  const MoveItProblem problem = graspProblem();
  const auto layered = makeCollisionModel(problem.scene);
  CollisionModelOptions off;
  off.hullLayer = false;
  const auto plain = makeCollisionModel(problem.scene, off);
  CollisionData layeredData(*layered), plainData(*plain);
  const Eigen::VectorXd goal = *problem.scene.queries.front().goal.joints;
  std::mt19937 random(81);
  std::normal_distribution<double> noise(0.0, 0.03);
  const ModelImplementation& impl = implementationOf(*layered);
  arcplan::robot::KinematicsData kinematics(layered->robot());
  int tighter = 0;
  for (int state = 0; state < 1000; ++state) {
    Eigen::VectorXd q = goal;
    for (Eigen::Index j = 0; j < q.size(); ++j) q[j] += noise(random);
    const DistanceReport a = distance(*layered, layeredData, q), b = distance(*plain, plainData, q);
    ASSERT_EQ(a.obstacleDistance, b.obstacleDistance) << "state " << state;
    ASSERT_EQ(a.selfDistance, b.selfDistance) << "state " << state;
    ASSERT_EQ(a.obstaclePair, b.obstaclePair) << "state " << state;
    for (const double c : {0.005, 0.01, 0.02})
      ASSERT_EQ(hasClearance(*layered, layeredData, q, c), hasClearance(*plain, plainData, q, c)) << "state " << state;
    // Every 10th state: the layer is tighter than the hulls for finger tips against the primitive obstacles
    // (the can inside the gripper's concavity), and still no more than the exact distance.
    if (state % 10 != 0) continue;
    arcplan::robot::forwardKinematics(layered->robot(), q, kinematics);
    for (int i = 0; i < static_cast<int>(impl.robotParts.size()); ++i) {
      const Part& part = impl.robotParts[i];
      if (layered->linkNames()[part.body].find("finger_tip") == std::string::npos || part.convexGeometry) continue;
      const Eigen::Isometry3d pose = kinematics.linkPoses[impl.robotPartLink[i]] * part.offset;
      for (const Part& obstacle : impl.obstacleParts) {
        if (!obstacle.containingMesh) continue;
        const double hull = hullGap(part, pose, obstacle, obstacle.offset, layered->options(), 1e9);
        const double contained = containingMeshGap(part, pose, obstacle, obstacle.offset, layered->options());
        if (contained <= hull + 1e-4) continue;
        ++tighter;
        EXPECT_LE(contained, partsDistance(part, pose, obstacle, obstacle.offset, true, off));
      }
    }
  }
  EXPECT_GT(tighter, 0);
}

}  // namespace
