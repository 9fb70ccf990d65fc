#include "convex_hull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/Eigenvalues>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace arcplan::collision::detail {
namespace {

// Beyond what qhull's rounding leaves outside, the hull is pushed out by this much more [m]: well
// below anything a query resolves (distances are exact to 1e-6 m), well above double rounding.
constexpr double kPushOut = 1e-12;

// qhull refuses flat or degenerate input (with a message on its error stream): those get no hull.
bool spansVolume(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 4) return false;
  const Eigen::Vector3d spread = principalAxes(points).spread;
  return spread[0] > 1e-12 * spread[2];
}

struct Facet {
  Eigen::Vector3d normal;  // outward, unit
  double offset;           // normal · x + offset = 0 on the plane, < 0 inside
  int corners[3];
};

// The hull of `corners`, scaled about its centre until it contains every one of `points` (corners
// among them).
std::shared_ptr<fcl::Convexd> hullContaining(const std::vector<Eigen::Vector3d>& corners,
                                             const std::vector<Eigen::Vector3d>& points) {
  if (!spansVolume(corners)) return nullptr;
  std::vector<coordT> coordinates;
  coordinates.reserve(3 * corners.size());
  for (const auto& p : corners) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});

  qhT context;
  qhT* qh = &context;
  qh_zero(qh, stderr);
  char options[] = "qhull Qt";  // triangulated facets
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Facet> facets;
  if (qh_new_qhull(qh, 3, static_cast<int>(corners.size()), coordinates.data(), False, options, nullptr, stderr) == 0) {
    std::vector<int> indexOf(corners.size(), -1);
    vertexT* vertex = nullptr;
    vertexT** vertexp = nullptr;
    FORALLvertices {
      const int id = qh_pointid(qh, vertex->point);
      indexOf[id] = static_cast<int>(vertices.size());
      vertices.push_back(corners[id]);
    }
    facetT* facet = nullptr;
    FORALLfacets {
      Facet f{Eigen::Vector3d(facet->normal[0], facet->normal[1], facet->normal[2]), facet->offset, {-1, -1, -1}};
      int k = 0;
      FOREACHvertex_(facet->vertices) {
        if (k < 3) f.corners[k] = indexOf[qh_pointid(qh, vertex->point)];
        ++k;
      }
      if (k != 3) continue;  // Qt gives triangles only
      const Eigen::Vector3d& a = vertices[f.corners[0]];
      if ((vertices[f.corners[1]] - a).cross(vertices[f.corners[2]] - a).dot(f.normal) < 0.0)
        std::swap(f.corners[1], f.corners[2]);
      facets.push_back(f);
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int shortLeft = 0, longLeft = 0;
  qh_memfreeshort(qh, &shortLeft, &longLeft);
  if (facets.size() < 4) return nullptr;

  // Scaling about an interior point c by (1 + s) moves every plane out by s × its distance from c.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& v : vertices) centre += v;
  centre /= static_cast<double>(vertices.size());
  // The planes of the triangles FCL is given, not qhull's facet planes: where qhull merged nearly
  // coplanar facets, a triangle's own plane differs a little from its merged facet's.
  double outside = 0.0, nearestPlane = std::numeric_limits<double>::infinity();
  for (const auto& f : facets) {
    const Eigen::Vector3d& a = vertices[f.corners[0]];
    const Eigen::Vector3d normal = (vertices[f.corners[1]] - a).cross(vertices[f.corners[2]] - a);
    if (!(normal.norm() > 1e-15)) continue;  // a sliver has no plane of its own; its neighbours bound it
    const Eigen::Vector3d unit = normal.normalized();
    nearestPlane = std::min(nearestPlane, -unit.dot(centre - a));
    for (const auto& p : points) outside = std::max(outside, unit.dot(p - a));
  }
  if (!(nearestPlane > 0.0)) return nullptr;
  const double scale = 1.0 + (outside + kPushOut) / nearestPlane;
  auto shapeVertices = std::make_shared<std::vector<Eigen::Vector3d>>();
  for (const auto& v : vertices) shapeVertices->push_back(centre + scale * (v - centre));
  auto faces = std::make_shared<std::vector<int>>();
  for (const auto& f : facets) faces->insert(faces->end(), {3, f.corners[0], f.corners[1], f.corners[2]});
  auto hull = std::make_shared<fcl::Convexd>(shapeVertices, static_cast<int>(facets.size()), faces);
  hull->computeLocalAABB();
  // Checked, not assumed: a hull that leaves a point outside is no lower bound, so that part has none.
  if (!(largestOutside(*hull, points) <= 0.0)) return nullptr;
  return hull;
}

}  // namespace

std::shared_ptr<fcl::Convexd> containingHull(const std::vector<Eigen::Vector3d>& points) {
  return hullContaining(points, points);
}

std::vector<Eigen::Vector3d> extremePoints(const std::vector<Eigen::Vector3d>& points, int directions) {
  std::vector<char> chosen(points.size(), 0);
  std::vector<Eigen::Vector3d> extremes;
  if (points.empty()) return extremes;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < directions; ++k) {
    const double z = 1.0 - 2.0 * (k + 0.5) / directions, r = std::sqrt(1.0 - z * z);
    const Eigen::Vector3d direction(r * std::cos(golden * k), r * std::sin(golden * k), z);
    std::size_t extreme = 0;
    for (std::size_t i = 1; i < points.size(); ++i) {
      if (direction.dot(points[i]) > direction.dot(points[extreme])) extreme = i;
    }
    if (!chosen[extreme]) extremes.push_back(points[extreme]);
    chosen[extreme] = 1;
  }
  return extremes;
}

std::shared_ptr<fcl::Convexd> coarseContainingHull(const std::vector<Eigen::Vector3d>& points, int directions) {
  if (points.empty() || directions < 4) return nullptr;
  // The hull of the points extreme along evenly spread directions follows the full hull to within about the
  // radius times 1 − cos(half their angular spacing).
  return hullContaining(extremePoints(points, directions), points);
}

double largestOutside(const fcl::Convexd& hull, const std::vector<Eigen::Vector3d>& points) {
  const auto& vertices = hull.getVertices();
  const auto& faces = hull.getFaces();
  double largest = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < faces.size(); k += static_cast<std::size_t>(faces[k]) + 1) {
    const Eigen::Vector3d& a = vertices[faces[k + 1]];
    const Eigen::Vector3d normal = (vertices[faces[k + 2]] - a).cross(vertices[faces[k + 3]] - a).normalized();
    for (const auto& p : points) largest = std::max(largest, normal.dot(p - a));
  }
  return largest;
}

PrincipalAxes principalAxes(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  return {centroid, solver.eigenvectors(), solver.eigenvalues()};
}

}  // namespace arcplan::collision::detail
