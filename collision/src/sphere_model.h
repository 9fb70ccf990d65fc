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
// After generation every vertex is checked to lie inside a fine sphere of its link and every fine
// sphere inside the coarse one (a failure throws arcplan::Error: it would be a defect).
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

// In the link frame of the body (ModelImplementation::linkCapsuleLink).
struct BodySpheres {
  Sphere coarse;
  std::vector<Sphere> fine;
};

// One entry per body (CollisionModel::linkNames() order).
using SphereModel = std::vector<BodySpheres>;

std::shared_ptr<const SphereModel> robotSphereModel(const ModelImplementation& impl,
                                                    const std::vector<std::string>& linkNames);

// The spheres whose union contains one part (in the link frame: Part::offset applied).
std::vector<Sphere> partSpheres(const Part& part);

// Throws arcplan::Error naming the link when a vertex of one of its parts lies outside every fine
// sphere, or a fine sphere sticks out of the coarse one.
void checkSphereModel(const ModelImplementation& impl, const SphereModel& spheres,
                      const std::vector<std::string>& linkNames);

}  // namespace arcplan::collision::detail
