// The 3D view's triangle meshes: the URDF's primitive shapes as the report draws them (through
// robot/primitive_mesh.h) are closed, outward-facing surfaces (their volume by the divergence theorem
// against the solids' formulas), and thinning keeps a mesh's shape within the triangle budget.
#include <cmath>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/robot/primitive_mesh.h"
#include "drawn_meshes.h"

namespace {

using arcplan::robot::signedVolume;
namespace detail = arcplan::report::detail;

constexpr double kPi = 3.14159265358979323846;

TEST(DrawnMeshes, BoxIsClosedAndFacesOutwards) {
  const auto box = arcplan::robot::boxMesh({0.1, 0.2, 0.3});
  EXPECT_EQ(box.vertices.size(), 8u);
  EXPECT_EQ(box.triangles.size(), 12u);
  EXPECT_NEAR(signedVolume(box), 0.1 * 0.2 * 0.3, 1e-12);
  for (const auto& v : box.vertices) {
    EXPECT_DOUBLE_EQ(std::abs(v.x()), 0.05);
    EXPECT_DOUBLE_EQ(std::abs(v.y()), 0.1);
    EXPECT_DOUBLE_EQ(std::abs(v.z()), 0.15);
  }
  EXPECT_THROW(arcplan::robot::boxMesh({0.1, 0.0, 0.3}), arcplan::Error);
}

TEST(DrawnMeshes, CylinderIsTheCircumscribedPrism) {
  const int n = 24;
  const double r = 0.05, length = 0.4;
  const auto cylinder = arcplan::robot::cylinderMesh({0, 0, -length / 2}, {0, 0, length / 2}, r, n);
  // A regular n-gon whose sides touch the circle of radius r has circumradius R = r / cos(pi / n)
  // and area (n/2) R^2 sin(2 pi / n).
  const double circumradius = r / std::cos(kPi / n);
  EXPECT_NEAR(signedVolume(cylinder), 0.5 * n * circumradius * circumradius * std::sin(2 * kPi / n) * length, 1e-12);
  EXPECT_EQ(cylinder.triangles.size(), 4u * n);
  for (const auto& v : cylinder.vertices) {
    const double fromAxis = std::hypot(v.x(), v.y());
    if (fromAxis > 1e-12) {  // a ring vertex (the cap centres are on the axis)
      EXPECT_NEAR(fromAxis, circumradius, 1e-12);
    }
    EXPECT_NEAR(std::abs(v.z()), length / 2, 1e-12);
  }
}

TEST(DrawnMeshes, SphereVerticesLieOnTheSphere) {
  const auto sphere = arcplan::robot::sphereMesh(0.3, 16);
  // 16 vertices on each of 7 rings of latitude and the two poles; a band of 2 triangles per facet
  // between rings and a fan of 16 at each pole.
  EXPECT_EQ(sphere.vertices.size(), 16u * 7u + 2u);
  EXPECT_EQ(sphere.triangles.size(), 2u * 16u * 6u + 2u * 16u);
  for (const auto& v : sphere.vertices) EXPECT_NEAR(v.norm(), 0.3, 1e-12);
  const double ball = 4.0 / 3.0 * kPi * 0.3 * 0.3 * 0.3;
  EXPECT_LT(signedVolume(sphere), ball);  // inscribed
  EXPECT_GT(signedVolume(sphere), 0.9 * ball);
  EXPECT_THROW(arcplan::robot::sphereMesh(0.0), arcplan::Error);
  EXPECT_THROW(arcplan::robot::sphereMesh(0.3, 3), arcplan::Error);
}

TEST(DrawnMeshes, ThinningKeepsTheShapeWithinTheBudget) {
  const auto fine = arcplan::robot::sphereMesh(1.0, 200);
  ASSERT_GT(fine.triangles.size(), 30000u);
  const auto coarse = detail::withAtMostTriangles(fine, 2000);
  EXPECT_LE(coarse.triangles.size(), 2000u);
  EXPECT_GT(coarse.triangles.size(), 500u);  // not thinned to nothing
  for (const auto& v : coarse.vertices) {
    EXPECT_LE(v.norm(), 1.0 + 1e-12);  // means of points on the sphere lie inside it ...
    EXPECT_GT(v.norm(), 0.97);         // ... close to it for cells a few percent of the diameter
  }
  const double ball = 4.0 / 3.0 * kPi;
  EXPECT_NEAR(signedVolume(coarse), ball, 0.05 * ball);  // still closed and facing outwards
  // Within the budget: the same mesh back.
  EXPECT_EQ(detail::withAtMostTriangles(fine, fine.triangles.size()).triangles, fine.triangles);
}

}  // namespace
