#pragma once
// A conservative sphere model of the robot, generated from its collision parts (parts.h): per link
// with geometry (a CollisionModel "body") fine spheres whose union contains every part, and one
// coarse sphere containing the fine ones. Used by the SIMD prefilter (sphere_prefilter.h), which may
// only call a state free when the spheres are clear, so containment is what matters:
//   - a mesh part lies in the convex hull of its vertices (Part::hullPoints). It is cut into slabs
//     along an axis; the part's points in a slab lie in the hull ∩ slab, a polytope whose corners are
//     vertices inside the slab or crossings of hull edges (segments between two vertices) with the
//     slab's planes. Their largest distance rho from the axis bounds every point's (distance from a
//     line is convex), so the ball around the slab's centre on the axis with radius
//     sqrt((slab length / 2)² + rho²) contains the part's points in the slab;
//   - URDF spheres are themselves, cylinders are slabs with rho = their radius, other parts slabs of
//     their bounding capsule plus balls at its ends.
// The fine spheres of a link are then grouped (SphereGroup), each group inside its own ball. After
// generation every vertex is checked to lie inside a fine sphere of its link and every fine sphere
// inside its group's ball and the coarse one (a failure throws arcplan::Error: it would be a defect).
//
// Generation costs a few milliseconds per robot; the result is cached in memory for the process,
// keyed by a hash of the geometry it was made from (sphere_model.cpp says why not on disk).
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "model_implementation.h"

namespace arcplan::collision::detail {

struct Sphere {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

// Consecutive fine spheres [begin, begin + count) of a body and a ball containing them.
struct SphereGroup {
  Sphere bound;
  int begin = 0, count = 0;
};

// In the link frame of the body (ModelImplementation::linkCapsuleLink). The fine spheres are ordered
// group by group; `groups` cover them all, in order. A body with a handful of fine spheres has one
// group (its bound is then the coarse sphere); a long one (an arm's dozen) has a group per few
// neighbours along it, so that the kernels test a few group balls, not every fine sphere, where
// the link is clear of something but its coarse sphere is not.
struct BodySpheres {
  Sphere coarse;
  std::vector<Sphere> fine;
  std::vector<SphereGroup> groups;
};

// One entry per body (CollisionModel::linkNames() order).
using SphereModel = std::vector<BodySpheres>;

std::shared_ptr<const SphereModel> robotSphereModel(const ModelImplementation& impl,
                                                    const std::vector<std::string>& linkNames);

// The spheres whose union contains one part (in the link frame: Part::offset applied).
std::vector<Sphere> partSpheres(const Part& part);

// Throws arcplan::Error naming the link when a vertex of one of its parts lies outside every fine
// sphere, a fine sphere sticks out of its group's ball or the coarse one, or the groups do not
// cover the fine spheres in order.
void checkSphereModel(const ModelImplementation& impl, const SphereModel& spheres,
                      const std::vector<std::string>& linkNames);

}  // namespace arcplan::collision::detail
