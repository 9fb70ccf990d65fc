// The generated UR10e link meshes (data/ur10e/meshes) read back through assimp: closed, outward,
// covering the link-radius cylinders of ur10e-facts.md §4.3, and as large as UR's own meshes.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/robot/mesh.h"
#include "arcplan/robot/primitive_mesh.h"
#include "arcplan/robot/robot_model.h"

namespace {

using arcplan::robot::TriangleMesh;
using Eigen::Vector3d;

// STL stores one vertex copy per triangle; identical coordinates are the same vertex.
TriangleMesh weldVertices(const TriangleMesh& mesh) {
  std::map<std::tuple<double, double, double>, int> indexOf;
  TriangleMesh welded;
  std::vector<int> remap(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const auto& p = mesh.vertices[i];
    const auto [it, inserted] =
        indexOf.emplace(std::make_tuple(p.x(), p.y(), p.z()), static_cast<int>(welded.vertices.size()));
    if (inserted) welded.vertices.push_back(p);
    remap[i] = it->second;
  }
  for (const auto& t : mesh.triangles) welded.triangles.emplace_back(remap[t[0]], remap[t[1]], remap[t[2]]);
  return welded;
}

// Closed and consistently oriented: every directed edge appears once and its reverse once.
void expectClosedAndConsistent(const TriangleMesh& mesh, const std::string& what) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  int bad = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) ++bad;
  }
  EXPECT_EQ(bad, 0) << what << ": edges not shared by exactly two oppositely oriented triangles";
}

// Connected components of the surface: triangles sharing an edge. (Cylinders on one axis share the
// centre vertex of an end disc, so a vertex criterion would glue separate solids together.)
std::vector<std::vector<int>> components(const TriangleMesh& mesh) {
  std::vector<int> parent(mesh.triangles.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::pair<int, int>, int> firstFaceOfEdge;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const auto edge = std::minmax(t[k], t[(k + 1) % 3]);
      const auto [it, inserted] = firstFaceOfEdge.emplace(edge, static_cast<int>(f));
      if (!inserted) parent[find(static_cast<int>(f))] = find(it->second);
    }
  }
  std::map<int, std::vector<int>> byRoot;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    byRoot[find(static_cast<int>(f))].push_back(static_cast<int>(f));
  std::vector<std::vector<int>> result;
  for (auto& [root, faces] : byRoot) result.push_back(std::move(faces));
  return result;
}

Vector3d normalOf(const TriangleMesh& mesh, int face) {
  const auto& t = mesh.triangles[face];
  return (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
}

// Generalised winding number (solid angles, Van Oosterom & Strackee): 1 inside a closed outward
// mesh, 0 outside; overlapping components add up.
double windingNumber(const TriangleMesh& mesh, const Vector3d& p) {
  double total = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vector3d a = mesh.vertices[t[0]] - p, b = mesh.vertices[t[1]] - p, c = mesh.vertices[t[2]] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * M_PI);
}

// Distance from p to a triangle: to the plane if the projection falls inside, else to the nearest edge.
double distanceToTriangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d n = (b - a).cross(c - a).normalized();
  const Vector3d projected = p - n * n.dot(p - a);
  const bool inside = n.dot((b - a).cross(projected - a)) >= 0 && n.dot((c - b).cross(projected - b)) >= 0 &&
                      n.dot((a - c).cross(projected - c)) >= 0;
  if (inside) return std::abs(n.dot(p - a));
  auto toSegment = [&p](const Vector3d& s, const Vector3d& e) {
    const double u = std::clamp((p - s).dot(e - s) / (e - s).squaredNorm(), 0.0, 1.0);
    return (s + u * (e - s) - p).norm();
  };
  return std::min({toSegment(a, b), toSegment(b, c), toSegment(c, a)});
}

double distanceToMesh(const TriangleMesh& mesh, const Vector3d& p) {
  double best = INFINITY;
  for (const auto& t : mesh.triangles) {
    best = std::min(best, distanceToTriangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]));
  }
  return best;
}

// ur10e-facts.md §4.3 as the table writes it: axis letter, centre of the other two coordinates
// (in x, y, z order, skipping the axis), radius, axial range.
struct FactsCylinder {
  char axis;
  double centre1, centre2, radius, from, to;
};

const std::map<std::string, std::vector<FactsCylinder>>& factsCylinders() {
  static const std::map<std::string, std::vector<FactsCylinder>> table{
      {"base_link_inertia", {{'z', 0, 0, 0.095, 0, 0.0993}}},
      {"shoulder_link", {{'z', 0, 0, 0.0765, -0.0817, 0.0939}, {'y', 0, 0, 0.0765, -0.0946, 0.0765}}},
      {"upper_arm_link",
       {{'z', 0, 0, 0.0767, 0.0948, 0.2694},
        {'x', 0, 0.1762, 0.0553, -0.6127, 0},
        {'x', 0, 0.1762, 0.075, -0.105, 0},
        {'x', 0, 0.1762, 0.0601, -0.6127, -0.535},
        {'z', -0.6127, 0, 0.0601, 0.0986, 0.2482}}},
      {"forearm_link",
       {{'z', 0, 0, 0.0588, -0.0189, 0.0987},
        {'x', 0, 0.0393, 0.0427, -0.57155, 0},
        {'x', 0, 0.0393, 0.0585, -0.09, 0},
        {'x', 0, 0.0393, 0.0455, -0.57155, -0.505},
        {'z', -0.57155, 0, 0.047, -0.0181, 0.1060}}},
      {"wrist_1_link", {{'z', 0, 0, 0.047, -0.0683, 0.0472}, {'y', 0, 0, 0.047, -0.0666, 0.0575}}},
      {"wrist_2_link", {{'z', 0, 0, 0.047, -0.0534, 0.0465}, {'y', 0, 0, 0.047, -0.0570, 0.0679}}},
      {"wrist_3_link", {{'z', 0, 0, 0.0452, -0.0489, 0}}},
  };
  return table;
}

// Points on the whole surface of a facts cylinder: its side (where the circumscribed mesh must hold
// them strictly inside) and its end discs (which may lie on a mesh cap).
struct SurfaceSample {
  Vector3d point;
  bool onSide;
};

std::vector<SurfaceSample> surfaceSamples(const FactsCylinder& c) {
  const int axisIndex = c.axis - 'x';
  const int first = axisIndex == 0 ? 1 : 0, second = axisIndex == 2 ? 1 : 2;
  auto point = [&](double axial, double angle, double radial) {
    Vector3d p;
    p[axisIndex] = axial;
    p[first] = c.centre1 + radial * std::cos(angle);
    p[second] = c.centre2 + radial * std::sin(angle);
    return p;
  };
  std::vector<SurfaceSample> samples;
  constexpr int kAngles = 40;  // not a multiple of the meshes' 32 segments: samples fall between vertices too
  for (int a = 0; a < kAngles; ++a) {
    const double angle = 2.0 * M_PI * (a + 0.5) / kAngles;
    for (int s = 1; s < 6; ++s) samples.push_back({point(c.from + (c.to - c.from) * s / 6.0, angle, c.radius), true});
    for (double fraction : {0.0, 0.5, 1.0}) {
      samples.push_back({point(c.from, angle, fraction * c.radius), false});
      samples.push_back({point(c.to, angle, fraction * c.radius), false});
    }
  }
  return samples;
}

TriangleMesh loadLinkMesh(const std::string& link) {
  const auto& model = arcplan::robot::ur10e();
  const auto& collisions = model.links()[model.linkIndex(link)].collisions;
  EXPECT_EQ(collisions.size(), 1u) << link;
  EXPECT_TRUE(collisions.at(0).origin.isApprox(Eigen::Isometry3d::Identity())) << link;
  return weldVertices(arcplan::robot::loadMesh(collisions.at(0).meshFile));
}

TEST(LinkMeshes, EveryCollisionLinkHasAClosedOutwardMesh) {
  for (const auto& [link, cylinders] : factsCylinders()) {
    const TriangleMesh mesh = loadLinkMesh(link);
    expectClosedAndConsistent(mesh, link);
    const auto parts = components(mesh);
    EXPECT_GE(parts.size(), cylinders.size()) << link;
    for (const auto& part : parts) {
      Vector3d centroid = Vector3d::Zero();
      std::set<int> vertices;
      double sixVolume = 0.0;
      for (int f : part) {
        const auto& t = mesh.triangles[f];
        for (int k = 0; k < 3; ++k) vertices.insert(t[k]);
        sixVolume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
      }
      for (int v : vertices) centroid += mesh.vertices[v];
      centroid /= static_cast<double>(vertices.size());
      EXPECT_GT(sixVolume, 0.0) << link << ": a component encloses negative volume (inward)";
      // Each component is a convex solid (a cylinder), so every face normal points away from its centre.
      int inward = 0;
      for (int f : part) {
        const auto& t = mesh.triangles[f];
        const Vector3d faceCentre = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
        if (normalOf(mesh, f).dot(faceCentre - centroid) <= 0.0) ++inward;
      }
      EXPECT_EQ(inward, 0) << link;
    }
  }
}

TEST(LinkMeshes, MeshesCoverTheLinkRadiusCylinders) {
  constexpr double kTolerance = 0.01;  // the coverage tolerance
  for (const auto& [link, cylinders] : factsCylinders()) {
    const TriangleMesh mesh = loadLinkMesh(link);
    int uncovered = 0, sideOutside = 0;
    double worstOutside = 0.0;
    for (const auto& cylinder : cylinders) {
      for (const auto& sample : surfaceSamples(cylinder)) {
        if (windingNumber(mesh, sample.point) > 0.5) continue;
        if (sample.onSide) ++sideOutside;
        const double distance = distanceToMesh(mesh, sample.point);
        worstOutside = std::max(worstOutside, distance);
        if (distance > kTolerance) ++uncovered;
      }
    }
    EXPECT_EQ(uncovered, 0) << link << ": worst sample " << worstOutside << " m outside";
    // Circumscribed polygons contain the cylinders: side points strictly inside, end discs at most on a cap.
    EXPECT_EQ(sideOutside, 0) << link;
    EXPECT_LT(worstOutside, 1e-6) << link;
  }
}

// The mesh bounding boxes of UR's own meshes in the ROS link frames (ur10e-facts.md §4.1): ours,
// built from the radius table, must span the same box within 1 cm (neither much smaller nor larger).
TEST(LinkMeshes, BoundingBoxesMatchUrMeshes) {
  const std::map<std::string, std::array<double, 6>> urBoxes{
      {"base_link_inertia", {-0.0950, 0.0950, -0.0950, 0.0950, 0, 0.0993}},
      {"shoulder_link", {-0.0764, 0.0764, -0.0946, 0.0764, -0.0817, 0.0939}},
      {"upper_arm_link", {-0.6724, 0.0767, -0.0764, 0.0764, 0.0948, 0.2694}},
      {"forearm_link", {-0.6176, 0.0588, -0.0580, 0.0580, -0.0189, 0.1060}},
      {"wrist_1_link", {-0.0470, 0.0470, -0.0666, 0.0575, -0.0683, 0.0472}},
      {"wrist_2_link", {-0.0470, 0.0470, -0.0570, 0.0679, -0.0534, 0.0465}},
      {"wrist_3_link", {-0.0448, 0.0448, -0.0511, 0.0455, -0.0489, 0.0000}},
  };
  for (const auto& [link, box] : urBoxes) {
    const TriangleMesh mesh = loadLinkMesh(link);
    Vector3d lower = Vector3d::Constant(INFINITY), upper = Vector3d::Constant(-INFINITY);
    for (const auto& v : mesh.vertices) {
      lower = lower.cwiseMin(v);
      upper = upper.cwiseMax(v);
    }
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_NEAR(lower[axis], box[2 * axis], 0.01) << link << " axis " << axis;
      EXPECT_NEAR(upper[axis], box[2 * axis + 1], 0.01) << link << " axis " << axis;
    }
  }
}

TEST(PrimitiveMesh, CylinderIsClosedOutwardAndHasThePolygonVolume) {
  const Vector3d start(0.1, -0.2, 0.3), end(-0.4, 0.5, 0.2);
  const double radius = 0.07;
  for (int segments : {3, 7, 32}) {
    const TriangleMesh mesh = arcplan::robot::cylinderMesh(start, end, radius, segments);
    expectClosedAndConsistent(mesh, "cylinder");
    // Circumscribed regular polygon: area N·r²·tan(pi/N).
    const double expected = segments * radius * radius * std::tan(M_PI / segments) * (end - start).norm();
    EXPECT_NEAR(arcplan::robot::signedVolume(mesh), expected, 1e-12) << segments;
    EXPECT_NEAR(windingNumber(mesh, (start + end) / 2), 1.0, 1e-9);
    EXPECT_NEAR(windingNumber(mesh, end + (end - start)), 0.0, 1e-9);
  }
}

TEST(PrimitiveMesh, AppendKeepsComponentsSeparate) {
  TriangleMesh mesh = arcplan::robot::cylinderMesh({0, 0, 0}, {0, 0, 1}, 0.1);
  const auto single = mesh;
  arcplan::robot::appendMesh(mesh, arcplan::robot::cylinderMesh({0, 0, 0.5}, {1, 0, 0.5}, 0.1));
  EXPECT_EQ(components(mesh).size(), 2u);
  EXPECT_EQ(mesh.vertices.size(), 2 * single.vertices.size());
  expectClosedAndConsistent(mesh, "two cylinders");
}

TEST(PrimitiveMesh, RejectsDegenerateInput) {
  EXPECT_THROW(arcplan::robot::cylinderMesh({0, 0, 0}, {0, 0, 1}, 0.0), arcplan::Error);
  EXPECT_THROW(arcplan::robot::cylinderMesh({0, 0, 0}, {0, 0, 0}, 0.1), arcplan::Error);
  EXPECT_THROW(arcplan::robot::cylinderMesh({0, 0, 0}, {0, 0, 1}, 0.1, 2), arcplan::Error);
}

}  // namespace
