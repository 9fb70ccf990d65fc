#include "sphere_model.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <mutex>
#include <utility>

#include "arcplan/common/error.h"
#include "convex_hull.h"

namespace arcplan::collision::detail {
namespace {

// Slabs about as long as the part is thick (its diameter about the axis, 2 rho): each ball's radius is then at most
// sqrt(2) times the part's rho (sqrt(rho^2 + (slab/2)^2)). Half as long (sqrt(1 + 1/4): 12 % wider) made RRTConnect +
// certified simplification on 30 MBM problems no faster (median of per-problem medians 21.9 -> 21.4 ms, noise; the
// time goes to the exact checks of pairs truly near a board, not to spheres that overlap too early).
constexpr double kSlabPerThickness = 1.0;
// Above this many vertices the segments between every two of them are too many to scan; every slab
// then takes the part's largest rho (still containing, only looser).
constexpr std::size_t kMaxScannedVertices = 600;
// Radii are grown by this much so that rounding in the construction never leaves a vertex a hair outside.
constexpr double kRadiusPadding = 1e-7;
// Bumped whenever the construction changes, so that cached models of an older one are not reused.
constexpr double kGeneratorVersion = 2.0;
// Fine spheres per group at most. On the thesis UR10e (12 fine spheres on each arm link) a batch of 8
// free-space states took 390-399 ns with groups of 4, 407 with 3, 420 with 6 (464 without groups).
constexpr int kFinePerGroup = 4;

// Balls along `axis` through `origin` covering points with axial coordinates in [t0, t1] whose
// distance from the axis is at most rho(k) in slab k (slabCount slabs of equal length).
template <class Rho>
std::vector<Sphere> slabBalls(const Eigen::Vector3d& origin, const Eigen::Vector3d& axis, double t0, double t1,
                              int slabCount, Rho rho) {
  std::vector<Sphere> balls;
  const double length = (t1 - t0) / slabCount;
  for (int k = 0; k < slabCount; ++k) {
    const double middle = t0 + (k + 0.5) * length;
    balls.push_back({origin + middle * axis, std::hypot(length / 2.0, rho(k)) + kRadiusPadding});
  }
  return balls;
}

int slabCountFor(double length, double thickness) {
  return std::max(1, static_cast<int>(std::ceil(length / (kSlabPerThickness * std::max(thickness, 1e-4)))));
}

// Slab balls around the convex hull of `points` along `axis` through their centroid (see sphere_model.h).
std::vector<Sphere> hullSlabBalls(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& centroid,
                                  const Eigen::Vector3d& axis) {
  const std::size_t n = points.size();
  std::vector<double> t(n), rho(n);
  double rhoMax = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d d = points[i] - centroid;
    t[i] = d.dot(axis);
    rho[i] = (d - t[i] * axis).norm();
    rhoMax = std::max(rhoMax, rho[i]);
  }
  const double t0 = *std::min_element(t.begin(), t.end()), t1 = *std::max_element(t.begin(), t.end());
  const int slabs = slabCountFor(t1 - t0, 2.0 * rhoMax);
  if (n > kMaxScannedVertices || t1 - t0 <= 0.0) {
    return slabBalls(centroid, axis, t0, t1, slabs, [rhoMax](int) { return rhoMax; });
  }
  const double length = (t1 - t0) / slabs;
  std::vector<double> slabRho(slabs, 0.0), planeRho(slabs + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const int k = std::clamp(static_cast<int>((t[i] - t0) / length), 0, slabs - 1);
    slabRho[k] = std::max(slabRho[k], rho[i]);
    // A vertex on (or rounded across) a slab boundary counts for both slabs.
    if (k > 0 && t[i] - (t0 + k * length) <= 1e-12) slabRho[k - 1] = std::max(slabRho[k - 1], rho[i]);
    if (k + 1 < slabs && (t0 + (k + 1) * length) - t[i] <= 1e-12) slabRho[k + 1] = std::max(slabRho[k + 1], rho[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if (t[i] == t[j]) continue;  // both are vertices, counted above
      const std::size_t lo = t[i] < t[j] ? i : j, hi = lo == i ? j : i;
      const int first = static_cast<int>(std::ceil((t[lo] - t0) / length)),
                last = static_cast<int>((t[hi] - t0) / length);
      for (int k = std::max(first, 0); k <= std::min(last, slabs); ++k) {
        const double plane = t0 + k * length, u = (plane - t[lo]) / (t[hi] - t[lo]);
        const Eigen::Vector3d d = points[lo] + u * (points[hi] - points[lo]) - centroid;
        planeRho[k] = std::max(planeRho[k], (d - d.dot(axis) * axis).norm());
      }
    }
  }
  return slabBalls(centroid, axis, t0, t1, slabs, [&](int k) {
    return std::max({slabRho[k], planeRho[k], planeRho[k + 1]});
  });
}

double volumeProxy(const std::vector<Sphere>& balls) {
  double sum = 0.0;
  for (const auto& ball : balls) sum += ball.radius * ball.radius * ball.radius;
  return sum;
}

// The slab balls along the principal axis (of the three) that gives the smallest total volume.
std::vector<Sphere> pointSpheres(const std::vector<Eigen::Vector3d>& points) {
  const PrincipalAxes principal = principalAxes(points);
  std::vector<Sphere> best;
  for (int k = 0; k < 3; ++k) {
    auto balls = hullSlabBalls(points, principal.centroid, principal.axes.col(k).normalized());
    if (best.empty() || volumeProxy(balls) < volumeProxy(best)) best = std::move(balls);
  }
  return best;
}

// Balls covering a capsule (segment start-end, radius): slabs of its cylinder and one ball per cap.
std::vector<Sphere> capsuleSpheres(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius) {
  const double length = (end - start).norm();
  std::vector<Sphere> balls{{start, radius + kRadiusPadding}, {end, radius + kRadiusPadding}};
  if (length > 0.0) {
    const auto middle = slabBalls(start, (end - start) / length, 0.0, length, slabCountFor(length, 2.0 * radius),
                                  [radius](int) { return radius; });
    balls.insert(balls.end(), middle.begin(), middle.end());
  }
  return balls;
}

Sphere enclosing(const std::vector<Sphere>& balls) {
  Eigen::Vector3d lower = Eigen::Vector3d::Constant(INFINITY), upper = -lower;
  for (const auto& ball : balls) {
    lower = lower.cwiseMin((ball.centre.array() - ball.radius).matrix());
    upper = upper.cwiseMax((ball.centre.array() + ball.radius).matrix());
  }
  Sphere result{(lower + upper) / 2.0, 0.0};
  for (const auto& ball : balls)
    result.radius = std::max(result.radius, (ball.centre - result.centre).norm() + ball.radius);
  result.radius += kRadiusPadding;
  return result;
}

// Orders the body's fine spheres along the principal axis of their centres and cuts them into
// groups of at most kFinePerGroup neighbours, as even as possible, each with its enclosing ball.
void groupFineSpheres(BodySpheres& body) {
  const int n = static_cast<int>(body.fine.size());
  const int groupCount = (n + kFinePerGroup - 1) / kFinePerGroup;
  if (groupCount <= 1) {
    body.groups = {{body.coarse, 0, n}};
    return;
  }
  std::vector<Eigen::Vector3d> centres;
  for (const auto& s : body.fine) centres.push_back(s.centre);
  const Eigen::Vector3d axis = principalAxes(centres).axes.col(2);
  std::stable_sort(body.fine.begin(), body.fine.end(),
                   [&](const Sphere& a, const Sphere& b) { return a.centre.dot(axis) < b.centre.dot(axis); });
  body.groups.clear();
  for (int g = 0, begin = 0; g < groupCount; ++g) {
    const int end = n * (g + 1) / groupCount;
    body.groups.push_back(
        {enclosing(std::vector<Sphere>(body.fine.begin() + begin, body.fine.begin() + end)), begin, end - begin});
    begin = end;
  }
}

// Everything the spheres are made from, as numbers: the cache key.
std::vector<double> geometryKey(const ModelImplementation& impl) {
  std::vector<double> key{kGeneratorVersion, static_cast<double>(impl.linkCapsules.size())};
  for (const Part& part : impl.robotParts) {
    key.push_back(part.body);
    key.push_back(static_cast<double>(part.solid.kind));
    const Eigen::Matrix4d offset = part.offset.matrix();
    key.insert(key.end(), offset.data(), offset.data() + 16);
    key.insert(key.end(), {part.solid.radius, part.solid.halfLength, part.capsule.radius});
    for (const auto* v : {&part.capsule.start, &part.capsule.end}) key.insert(key.end(), v->data(), v->data() + 3);
    for (const auto& p : part.hullPoints) key.insert(key.end(), p.data(), p.data() + 3);
  }
  return key;
}

std::uint64_t hashOf(const std::vector<double>& key) {
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a, 64 bit
  for (const double value : key) {
    unsigned char bytes[sizeof(double)];
    std::memcpy(bytes, &value, sizeof(double));
    for (const unsigned char byte : bytes) hash = (hash ^ byte) * 1099511628211ull;
  }
  return hash;
}

SphereModel generate(const ModelImplementation& impl) {
  SphereModel model(impl.linkCapsules.size());
  for (const Part& part : impl.robotParts) {
    const auto balls = partSpheres(part);
    auto& fine = model[static_cast<std::size_t>(part.body)].fine;
    fine.insert(fine.end(), balls.begin(), balls.end());
  }
  for (auto& body : model) {
    if (body.fine.empty()) continue;
    body.coarse = enclosing(body.fine);
    groupFineSpheres(body);
  }
  return model;
}

}  // namespace

std::vector<Sphere> partSpheres(const Part& part) {
  if (part.solid.kind == Solid::Kind::Sphere) return {{part.offset.translation(), part.solid.radius + kRadiusPadding}};
  if (part.solid.kind == Solid::Kind::Cylinder) {
    const Eigen::Vector3d axis = part.offset.linear().col(2);
    const double half = part.solid.halfLength, radius = part.solid.radius;
    return slabBalls(part.offset.translation(), axis, -half, half, slabCountFor(2.0 * half, 2.0 * radius),
                     [radius](int) { return radius; });
  }
  if (!part.hullPoints.empty()) {
    std::vector<Eigen::Vector3d> points;
    points.reserve(part.hullPoints.size());
    for (const auto& p : part.hullPoints) points.push_back(part.offset * p);
    return pointSpheres(points);
  }
  return capsuleSpheres(part.offset * part.capsule.start, part.offset * part.capsule.end, part.capsule.radius);
}

void checkSphereModel(const ModelImplementation& impl, const SphereModel& spheres,
                      const std::vector<std::string>& linkNames) {
  const auto inside = [](const Eigen::Vector3d& p, const Sphere& s) { return (p - s.centre).norm() <= s.radius; };
  for (const Part& part : impl.robotParts) {
    const BodySpheres& body = spheres[static_cast<std::size_t>(part.body)];
    for (const auto& vertex : part.hullPoints) {
      const Eigen::Vector3d p = part.offset * vertex;
      if (std::none_of(body.fine.begin(), body.fine.end(), [&](const Sphere& s) { return inside(p, s); })) {
        throw Error("sphere model: a vertex of link " + linkNames[part.body] + " lies outside every sphere");
      }
    }
  }
  const auto within = [](const Sphere& s, const Sphere& ball) {
    return (s.centre - ball.centre).norm() + s.radius <= ball.radius;
  };
  for (std::size_t b = 0; b < spheres.size(); ++b) {
    const BodySpheres& body = spheres[b];
    int next = 0;
    for (const auto& group : body.groups) {
      if (group.begin != next || group.count <= 0) {
        throw Error("sphere model: the sphere groups of link " + linkNames[b] + " do not cover its spheres in order");
      }
      for (int k = group.begin; k < group.begin + group.count; ++k) {
        if (!within(body.fine[k], group.bound) || !within(body.fine[k], body.coarse)) {
          throw Error("sphere model: a sphere of link " + linkNames[b] + " sticks out of its bounding sphere");
        }
      }
      next += group.count;
    }
    if (next != static_cast<int>(body.fine.size())) {
      throw Error("sphere model: the sphere groups of link " + linkNames[b] + " do not cover its spheres in order");
    }
  }
}

// Not on disk: generating takes milliseconds (docs/collision.md), a cache file would be one more
// input to parse and trust, and the vertices would have to be checked against it anyway.
std::shared_ptr<const SphereModel> robotSphereModel(const ModelImplementation& impl,
                                                    const std::vector<std::string>& linkNames) {
  static std::mutex mutex;
  static std::multimap<std::uint64_t, std::pair<std::vector<double>, std::shared_ptr<const SphereModel>>> cache;
  std::vector<double> key = geometryKey(impl);
  const std::uint64_t hash = hashOf(key);
  std::shared_ptr<const SphereModel> model;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto [first, last] = cache.equal_range(hash);
    for (auto it = first; it != last && !model; ++it) {
      if (it->second.first == key) model = it->second.second;
    }
  }
  if (!model) {
    model = std::make_shared<const SphereModel>(generate(impl));
    const std::lock_guard<std::mutex> lock(mutex);
    cache.emplace(hash, std::make_pair(std::move(key), model));
  }
  checkSphereModel(impl, *model, linkNames);
  return model;
}

}  // namespace arcplan::collision::detail
