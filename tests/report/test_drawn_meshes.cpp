// The 3D view's triangle meshes: primitive shapes tessellated as closed, outward-facing surfaces
// (their volume by the divergence theorem against the solids' formulas) and thinning that keeps a
// mesh's shape within the triangle budget.
#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "drawn_meshes.h"

namespace {

using arcplan::robot::TriangleMesh;
namespace detail = arcplan::report::detail;

constexpr double kPi = 3.14159265358979323846;

// Sum of the signed tetrahedra (origin, triangle): the enclosed volume when every triangle is
// counter-clockwise seen from outside, minus it when they face inwards.
double signedVolume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (const auto& t : mesh.triangles) {
    volume += mesh.vertices[t.x()].dot(mesh.vertices[t.y()].cross(mesh.vertices[t.z()])) / 6.0;
  }
  return volume;
}

TEST(DrawnMeshes, BoxIsClosedAndFacesOutwards) {
  const auto box = detail::boxMesh({0.1, 0.2, 0.3});
  EXPECT_EQ(box.vertices.size(), 8u);
  EXPECT_EQ(box.triangles.size(), 12u);
  EXPECT_NEAR(signedVolume(box), 0.1 * 0.2 * 0.3, 1e-12);
  for (const auto& v : box.vertices) {
    EXPECT_DOUBLE_EQ(std::abs(v.x()), 0.05);
    EXPECT_DOUBLE_EQ(std::abs(v.z()), 0.15);
  }
}

TEST(DrawnMeshes, CylinderIsTheInscribedPrism) {
  const int n = 24;
  const auto cylinder = detail::cylinderMesh(0.05, 0.4, n);
  // A regular n-gon of circumradius r has area (n/2) r^2 sin(2 pi / n).
  EXPECT_NEAR(signedVolume(cylinder), 0.5 * n * 0.05 * 0.05 * std::sin(2 * kPi / n) * 0.4, 1e-12);
  EXPECT_EQ(cylinder.triangles.size(), 4u * n);
}

TEST(DrawnMeshes, SphereVerticesLieOnTheSphere) {
  const auto sphere = detail::sphereMesh(0.3, 16);
  for (const auto& v : sphere.vertices) EXPECT_NEAR(v.norm(), 0.3, 1e-12);
  const double ball = 4.0 / 3.0 * kPi * 0.3 * 0.3 * 0.3;
  EXPECT_LT(signedVolume(sphere), ball);  // inscribed
  EXPECT_GT(signedVolume(sphere), 0.9 * ball);
}

TEST(DrawnMeshes, ThinningKeepsTheShapeWithinTheBudget) {
  const auto fine = detail::sphereMesh(1.0, 200);
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
