// Collision geometry to FCL parts: meshes split into components, solids and their bounding capsules,
// and the primitive shapes — one concept, a little over 400 lines because the capsule fits belong to it.
#include "parts.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kIOS.h>

#include "arcplan/common/error.h"
#include "containing_meshes.h"
#include "convex_hull.h"

namespace arcplan::collision::detail {
namespace {

// Beyond this many components a mesh (a scanned scene, a CAD assembly) is one part: per-component
// parts would multiply the pairs to test.
constexpr std::size_t kMaxComponentParts = 32;
// Bounding volumes are padded so rounding never makes them smaller than what they bound.
constexpr double kBoundPadding = 1e-6;
// Hulls with more vertices than this also get a coarse hull of the points extreme along this many
// directions (fewer vertices: FCL's support search walks the vertex graph of the whole hull).
constexpr int kCoarseHullVertices = 128, kCoarseHullDirections = 64;
// Witness points: the vertices extreme along this many directions. On MBM's bookshelf_thin 0004 (RRTConnect, 1 cm)
// they prove 616 of the 674 gripper-board pairs that the exact distance (0.56 ms each) finds too close; all
// vertices would prove 657, at up to 20 000 points per part.
constexpr int kWitnessDirections = 64;

template <typename BV>
std::shared_ptr<fcl::CollisionGeometryd> makeBvh(const robot::TriangleMesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(mesh.vertices.size()));
  model->addSubModel(mesh.vertices, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

std::shared_ptr<fcl::CollisionGeometryd> makeBvh(const robot::TriangleMesh& mesh, BoundingVolume boundingVolume) {
  switch (boundingVolume) {
    case BoundingVolume::AABB:
      return makeBvh<fcl::AABBd>(mesh);
    case BoundingVolume::OBB:
      return makeBvh<fcl::OBBd>(mesh);
    case BoundingVolume::RSS:
      return makeBvh<fcl::RSSd>(mesh);
    case BoundingVolume::kIOS:
      return makeBvh<fcl::kIOSd>(mesh);
    case BoundingVolume::OBBRSS:
      return makeBvh<fcl::OBBRSSd>(mesh);
  }
  throw Error("unknown bounding-volume type");
}

// Tightest capsule (over a few radii) along `axis` through `centre` around points given by their
// axial coordinate t and distance rho from the axis: a point outside [t0, t1] is inside the end
// cap if |t - t_end| <= sqrt(R² - rho²).
Capsule fitCapsuleToProfile(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis,
                            const std::vector<std::pair<double, double>>& profile) {
  double rhoMax = 0.0;
  for (const auto& [t, rho] : profile) rhoMax = std::max(rhoMax, rho);
  rhoMax = std::max(rhoMax, 1e-9);
  Capsule best;
  double bestVolume = INFINITY;
  for (int step = 0; step <= 60; ++step) {
    double radius = rhoMax * (1.0 + 0.02 * step);
    double t0 = INFINITY, t1 = -INFINITY;
    for (const auto& [t, rho] : profile) {
      const double cap = std::sqrt(std::max(0.0, radius * radius - rho * rho));
      t0 = std::min(t0, t + cap);
      t1 = std::max(t1, t - cap);
    }
    if (t0 > t1) {  // a ball is enough: centre it between the two limits
      t0 = t1 = (t0 + t1) / 2.0;
      radius = 0.0;
      for (const auto& [t, rho] : profile) radius = std::max(radius, std::hypot(t - t0, rho));
    }
    const double volume = M_PI * radius * radius * (t1 - t0) + 4.0 / 3.0 * M_PI * radius * radius * radius;
    if (volume < bestVolume) {
      bestVolume = volume;
      best = {centre + t0 * axis, centre + t1 * axis, radius + kBoundPadding};
    }
  }
  return best;
}

// Tries the three principal axes of the points and keeps the smallest capsule.
Capsule fitCapsule(const std::vector<Eigen::Vector3d>& points) {
  const PrincipalAxes principal = principalAxes(points);
  const Eigen::Vector3d& centre = principal.centroid;
  Capsule best;
  double bestVolume = INFINITY;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d axis = principal.axes.col(k).normalized();
    std::vector<std::pair<double, double>> profile;
    profile.reserve(points.size());
    for (const auto& p : points) {
      const double t = (p - centre).dot(axis);
      profile.emplace_back(t, (p - centre - t * axis).norm());
    }
    const Capsule capsule = fitCapsuleToProfile(centre, axis, profile);
    const double volume = M_PI * capsule.radius * capsule.radius * (capsule.end - capsule.start).norm() +
                          4.0 / 3.0 * M_PI * std::pow(capsule.radius, 3);
    if (volume < bestVolume) {
      bestVolume = volume;
      best = capsule;
    }
  }
  return best;
}

robot::TriangleMesh weld(const robot::TriangleMesh& mesh) {
  std::map<std::tuple<double, double, double>, int> indexOf;
  robot::TriangleMesh welded;
  std::vector<int> remap(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const auto& p = mesh.vertices[i];
    const auto [it, inserted] =
        indexOf.emplace(std::make_tuple(p.x(), p.y(), p.z()), static_cast<int>(welded.vertices.size()));
    if (inserted) welded.vertices.push_back(p);
    remap[i] = it->second;
  }
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3i w(remap[t[0]], remap[t[1]], remap[t[2]]);
    if (w[0] != w[1] && w[1] != w[2] && w[0] != w[2]) welded.triangles.push_back(w);  // drop degenerate slivers
  }
  return welded;
}

// Triangle indices of each edge-connected component.
std::vector<std::vector<int>> edgeComponents(const robot::TriangleMesh& mesh) {
  std::vector<int> parent(mesh.triangles.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  auto find = [&parent](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::pair<int, int>, int> faceOfEdge;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const auto [it, inserted] = faceOfEdge.emplace(std::minmax(t[k], t[(k + 1) % 3]), static_cast<int>(f));
      if (!inserted) parent[find(static_cast<int>(f))] = find(it->second);
    }
  }
  std::map<int, std::vector<int>> byRoot;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    byRoot[find(static_cast<int>(f))].push_back(static_cast<int>(f));
  std::vector<std::vector<int>> components;
  for (auto& entry : byRoot) components.push_back(std::move(entry.second));
  return components;
}

robot::TriangleMesh subMesh(const robot::TriangleMesh& mesh, const std::vector<int>& faces) {
  robot::TriangleMesh part;
  std::map<int, int> local;
  for (int f : faces) {
    Eigen::Vector3i t;
    for (int k = 0; k < 3; ++k) {
      const auto [it, inserted] = local.emplace(mesh.triangles[f][k], static_cast<int>(part.vertices.size()));
      if (inserted) part.vertices.push_back(mesh.vertices[mesh.triangles[f][k]]);
      t[k] = it->second;
    }
    part.triangles.push_back(t);
  }
  return part;
}

// Every directed edge once and its reverse once: a closed, consistently oriented surface.
bool isClosed(const robot::TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  return std::all_of(directed.begin(), directed.end(), [&directed](const auto& entry) {
    const auto reverse = directed.find({entry.first.second, entry.first.first});
    return entry.second == 1 && reverse != directed.end() && reverse->second == 1;
  });
}

double sixTimesVolume(const robot::TriangleMesh& mesh) {
  double volume = 0.0;
  for (const auto& t : mesh.triangles)
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  return volume;
}

// A closed mesh as a solid: its face planes if it is convex, else the (outward) triangles.
Solid closedMeshSolid(robot::TriangleMesh mesh) {
  if (sixTimesVolume(mesh) < 0.0) {
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  }
  double extent = 0.0;
  for (const auto& v : mesh.vertices) extent = std::max(extent, v.cwiseAbs().maxCoeff());
  const double tolerance = 1e-6 * std::max(extent, 1.0);  // STL stores floats
  Solid solid;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d normal = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
    if (normal.norm() == 0.0) continue;
    const Eigen::Vector4d plane((normal.normalized()).x(), normal.normalized().y(), normal.normalized().z(),
                                normal.normalized().dot(a));
    const bool known = std::any_of(solid.planes.begin(), solid.planes.end(), [&plane](const Eigen::Vector4d& p) {
      return (p - plane).cwiseAbs().maxCoeff() < 1e-9;
    });
    if (!known) solid.planes.push_back(plane);
  }
  const bool convex = std::all_of(solid.planes.begin(), solid.planes.end(), [&](const Eigen::Vector4d& plane) {
    return std::all_of(mesh.vertices.begin(), mesh.vertices.end(),
                       [&](const Eigen::Vector3d& v) { return plane.head<3>().dot(v) <= plane[3] + tolerance; });
  });
  if (convex) {
    solid.kind = Solid::Kind::Convex;
  } else {
    solid.planes.clear();
    solid.kind = Solid::Kind::ClosedMesh;
    solid.mesh = std::move(mesh);
  }
  return solid;
}

Part makeMeshPart(const robot::TriangleMesh& mesh, Solid solid, const CollisionModelOptions& options) {
  Part part;
  part.collisionGeometry = makeBvh(mesh, options.collisionBoundingVolume);
  part.distanceGeometry = options.distanceBoundingVolume == options.collisionBoundingVolume
                              ? part.collisionGeometry
                              : makeBvh(mesh, options.distanceBoundingVolume);
  part.capsule = fitCapsule(mesh.vertices);
  if (solid.kind == Solid::Kind::Convex) {
    auto faces = std::make_shared<std::vector<int>>();
    for (const auto& t : mesh.triangles) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
    part.convexGeometry =
        std::make_shared<fcl::Convexd>(std::make_shared<const std::vector<Eigen::Vector3d>>(mesh.vertices),
                                       static_cast<int>(mesh.triangles.size()), faces);
    part.convexGeometry->computeLocalAABB();
    part.hullGeometry = part.convexGeometry;
  } else {
    const auto hull = containingHull(mesh.vertices);
    part.hullGeometry = hull;
    if (hull && static_cast<int>(hull->getVertices().size()) > kCoarseHullVertices)
      part.coarseHullGeometry = coarseContainingHull(mesh.vertices, kCoarseHullDirections);
  }
  part.solid = std::move(solid);
  part.referencePoint = mesh.vertices.front();
  part.hullPoints = mesh.vertices;
  part.witnessPoints = extremePoints(mesh.vertices, kWitnessDirections);
  part.triangleCount = static_cast<int>(mesh.triangles.size());
  return part;
}

}  // namespace

bool Solid::contains(const Eigen::Vector3d& point) const {
  switch (kind) {
    case Kind::None:
      return false;
    case Kind::Sphere:
      return point.squaredNorm() <= radius * radius;
    case Kind::Box:
      return (point.cwiseAbs() - halfExtents).maxCoeff() <= 0.0;
    case Kind::Cylinder:
      return std::abs(point.z()) <= halfLength && point.head<2>().squaredNorm() <= radius * radius;
    case Kind::Convex:
      return std::all_of(planes.begin(), planes.end(),
                         [&point](const Eigen::Vector4d& plane) { return plane.head<3>().dot(point) <= plane[3]; });
    case Kind::ClosedMesh:
      break;
  }
  // Signed crossings of a ray (Möller–Trumbore): leaving through an outward face counts +1,
  // entering -1; the sum is the number of (possibly overlapping) components around the point.
  const Eigen::Vector3d direction = Eigen::Vector3d(0.4172, 0.5521, 0.7219).normalized();
  int crossings = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d edge1 = mesh.vertices[t[1]] - a, edge2 = mesh.vertices[t[2]] - a;
    const Eigen::Vector3d p = direction.cross(edge2);
    const double determinant = edge1.dot(p);
    if (std::abs(determinant) < 1e-15) continue;
    const Eigen::Vector3d s = point - a;
    const double u = s.dot(p) / determinant;
    if (u < 0.0 || u > 1.0) continue;
    const Eigen::Vector3d q = s.cross(edge1);
    const double v = direction.dot(q) / determinant;
    if (v < 0.0 || u + v > 1.0) continue;
    if (edge2.dot(q) / determinant <= 0.0) continue;  // behind the point
    crossings += determinant < 0.0 ? 1 : -1;          // det = -(normal · direction)
  }
  return crossings > 0;
}

std::vector<Part> meshParts(const robot::TriangleMesh& input, const CollisionModelOptions& options) {
  const robot::TriangleMesh mesh = weld(input);
  if (mesh.triangles.empty()) throw Error("mesh has no non-degenerate triangles");
  const auto components = edgeComponents(mesh);
  std::vector<Part> parts;
  if (components.size() > kMaxComponentParts) {
    const bool allClosed = std::all_of(components.begin(), components.end(),
                                       [&mesh](const auto& faces) { return isClosed(subMesh(mesh, faces)); });
    Solid solid;
    if (allClosed) {
      solid.kind = Solid::Kind::ClosedMesh;
      solid.mesh = mesh;
    }
    parts.push_back(makeMeshPart(mesh, std::move(solid), options));
    return parts;
  }
  for (const auto& faces : components) {
    robot::TriangleMesh component = subMesh(mesh, faces);
    Solid solid = isClosed(component) ? closedMeshSolid(component) : Solid{};
    parts.push_back(makeMeshPart(component, std::move(solid), options));
  }
  return parts;
}

namespace {

void setContainingMesh(Part& part, const ContainingMesh& containing, BoundingVolume boundingVolume) {
  part.containingMesh = makeBvh(containing.mesh, boundingVolume);
  part.containingSolid.kind = Solid::Kind::Convex;
  for (const auto& t : containing.mesh.triangles) {
    const Eigen::Vector3d& a = containing.mesh.vertices[t[0]];
    const Eigen::Vector3d normal =
        (containing.mesh.vertices[t[1]] - a).cross(containing.mesh.vertices[t[2]] - a).normalized();
    // Padded outward: a point on a face counts as inside, where the layer answers nothing.
    part.containingSolid.planes.emplace_back(normal.x(), normal.y(), normal.z(), normal.dot(a) + kBoundPadding);
  }
}

}  // namespace

Part spherePart(double radius, BoundingVolume containingMesh) {
  Part part;
  part.collisionGeometry = part.distanceGeometry = part.convexGeometry = part.hullGeometry =
      std::make_shared<fcl::Sphered>(radius);
  part.capsule.radius = radius + kBoundPadding;
  part.solid.kind = Solid::Kind::Sphere;
  part.solid.radius = radius;
  setContainingMesh(part, containingSphereMesh(radius), containingMesh);
  return part;
}

Part boxPart(const Eigen::Vector3d& size) {
  Part part;
  part.collisionGeometry = part.distanceGeometry = part.convexGeometry = part.hullGeometry =
      std::make_shared<fcl::Boxd>(size.x(), size.y(), size.z());
  std::vector<Eigen::Vector3d> corners;
  for (int corner = 0; corner < 8; ++corner) {
    corners.emplace_back((corner & 1 ? 0.5 : -0.5) * size.x(), (corner & 2 ? 0.5 : -0.5) * size.y(),
                         (corner & 4 ? 0.5 : -0.5) * size.z());
  }
  part.capsule = fitCapsule(corners);
  part.hullPoints = part.witnessPoints = corners;
  part.boxHalfExtents = size / 2.0;
  part.solid.kind = Solid::Kind::Box;
  part.solid.halfExtents = size / 2.0;
  return part;
}

Part cylinderPart(double radius, double length, BoundingVolume containingMesh) {
  Part part;
  part.collisionGeometry = part.distanceGeometry = part.convexGeometry = part.hullGeometry =
      std::make_shared<fcl::Cylinderd>(radius, length);
  part.capsule = fitCapsuleToProfile(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                                     {{-length / 2.0, radius}, {length / 2.0, radius}});
  part.solid.kind = Solid::Kind::Cylinder;
  part.solid.radius = radius;
  part.solid.halfLength = length / 2.0;
  setContainingMesh(part, containingCylinderMesh(radius, length), containingMesh);
  return part;
}

Capsule enclosingCapsule(const std::vector<Capsule>& capsules) {
  std::vector<Eigen::Vector3d> ends;
  double largestRadius = 0.0;
  for (const auto& c : capsules) {
    ends.push_back(c.start);
    ends.push_back(c.end);
    largestRadius = std::max(largestRadius, c.radius);
  }
  // The fitted capsule contains the hull of the end points, so every segment; growing its radius
  // by the largest part radius then contains every part capsule.
  Capsule enclosing = fitCapsule(ends);
  enclosing.radius += largestRadius;
  return enclosing;
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> segmentClosestPoints(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                                 const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  // Clamped parameters, as in Ericson, Real-Time Collision Detection §5.1.9.
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kTiny = 1e-18;
  double s = 0.0, t = 0.0;
  if (a <= kTiny && e <= kTiny) return {p0, q0};
  if (a <= kTiny) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kTiny) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denominator = a * e - b * b;
      s = denominator > kTiny ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return {p0 + s * d1, q0 + t * d2};
}

double segmentDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                       const Eigen::Vector3d& q1) {
  const auto [onFirst, onSecond] = segmentClosestPoints(p0, p1, q0, q1);
  return (onFirst - onSecond).norm();
}

CapsuleBoxGaps capsuleBoxGaps(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius,
                              const Eigen::Vector3d& halfExtents) {
  const Eigen::Vector3d lower = start.cwiseMin(end).array() - radius;
  const Eigen::Vector3d upper = start.cwiseMax(end).array() + radius;
  const Eigen::Vector3d above = lower - halfExtents, below = -halfExtents - upper;
  return {above.cwiseMax(below), (above.array() > below.array()).matrix()};
}

double capsuleBoxLowerBound(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius,
                            const Eigen::Vector3d& halfExtents) {
  const Eigen::Vector3d gap = capsuleBoxGaps(start, end, radius, halfExtents).gap;
  if (gap.maxCoeff() <= 0.0) return gap.maxCoeff();
  return gap.cwiseMax(0.0).norm();
}

}  // namespace arcplan::collision::detail
