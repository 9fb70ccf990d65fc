#include "arcplan/collision/endpoint_clearance.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "arcplan/common/error.h"
#include "model_implementation.h"
#include "motion_clearance.h"

namespace arcplan::collision {
namespace {

void checkDistance(double value, const char* what) {
  if (!std::isfinite(value) || value < 0.0) {
    throw Error(std::string("endpoint clearance: ") + what + " must be a finite distance >= 0 m, got " +
                std::to_string(value));
  }
}

}  // namespace

EndpointClearance::EndpointClearance(double clearance, double motionClearance)
    : clearance_(clearance), motionClearance_(std::max(clearance, motionClearance)) {
  checkDistance(clearance, "clearance");
  checkDistance(motionClearance, "motion clearance");
}

EndpointClearance::EndpointClearance(const CollisionModel& model, double clearance, double motionClearance,
                                     const std::vector<robot::JointVector>& endpoints)
    : EndpointClearance(clearance, motionClearance) {
  const int dof = model.robot().dof();
  // The certified motion check's own per-body, per-joint reach (the D_jL of motionBound), built with
  // the model: the zones bound displacements exactly as the motion check does.
  reach_ = detail::implementationOf(model).jointReach;
  CollisionData data(model);
  for (const robot::JointVector& endpoint : endpoints) {
    if (endpoint.size() != dof) {
      throw Error("endpoint clearance: an endpoint has " + std::to_string(endpoint.size()) + " joints, the robot " +
                  std::to_string(dof));
    }
    const double e = distance(model, data, endpoint).minimum();
    if (!(e > 0.0) || !(e < motionClearance_)) continue;  // in contact (stays invalid), or clear enough
    const double relaxed = kApproachZoneFraction * e;
    zones_.push_back({endpoint, e, std::min(clearance_, relaxed),
                      std::max(detail::kSmallestMinimumClearance, std::min(motionClearance_, relaxed))});
  }
}

double EndpointClearance::smallestStateClearance() const {
  double smallest = clearance_;
  for (const ApproachZone& zone : zones_) smallest = std::min(smallest, zone.stateClearance);
  return smallest;
}

double EndpointClearance::displacement(const robot::JointRef& endpoint, const robot::JointRef& q) const {
  if (reach_.size() == 0) return 0.0;
  return (reach_ * (q - endpoint).cwiseAbs()).maxCoeff();
}

double EndpointClearance::nearestFraction(const robot::JointRef& endpoint, const robot::JointRef& qa,
                                          const robot::JointRef& qb) const {
  // f(s) = max over bodies of Σ_j D_jL·|qa_j + s·Δ_j − endpoint_j| is convex in s (a maximum of sums
  // of absolute values of affine functions), so a ternary search finds its minimum on [0, 1]. After
  // 80 steps the interval is (2/3)^80 < 1e-14 wide; f changes by at most max_L Σ_j D_jL·|Δ_j| per
  // unit of s (a few metres), so f there is within 1e-13 m of the true minimum, from above.
  const robot::JointVector delta = qb - qa;
  const auto f = [&](double s) { return displacement(endpoint, qa + s * delta); };
  double low = 0.0, high = 1.0;
  for (int step = 0; step < 80; ++step) {
    const double a = low + (high - low) / 3.0, b = high - (high - low) / 3.0;
    if (f(a) <= f(b)) {
      high = b;
    } else {
      low = a;
    }
  }
  const double middle = 0.5 * (low + high);
  if (f(0.0) <= std::min(f(1.0), f(middle))) return 0.0;
  return f(1.0) <= f(middle) ? 1.0 : middle;
}

double EndpointClearance::closestApproach(const robot::JointRef& endpoint, const robot::JointRef& qa,
                                          const robot::JointRef& qb) const {
  return displacement(endpoint, qa + nearestFraction(endpoint, qa, qb) * (qb - qa));
}

std::vector<MotionPiece> EndpointClearance::motionPieces(const robot::JointRef& qa, const robot::JointRef& qb) const {
  const robot::JointVector delta = qb - qa;
  struct Interval {
    double from, to, clearance;
  };
  std::vector<Interval> inside;
  std::vector<double> cuts{0.0, 1.0};
  for (const ApproachZone& zone : zones_) {
    if (zone.motionClearance >= motionClearance_) continue;
    const auto inZone = [&](double s) { return displacement(zone.endpoint, qa + s * delta) <= kApproachZoneLength; };
    const double nearest = nearestFraction(zone.endpoint, qa, qb);
    if (!inZone(nearest)) continue;
    // The displacement is convex, so the zone holds one interval of s around `nearest`; its ends are
    // bisected to 2^-60 and kept on the inside, so every s of the interval lies in the zone.
    const auto edge = [&](double in, double out) {
      if (inZone(out)) return out;
      for (int step = 0; step < 60; ++step) {
        const double s = 0.5 * (in + out);
        (inZone(s) ? in : out) = s;
      }
      return in;
    };
    inside.push_back({edge(nearest, 0.0), edge(nearest, 1.0), zone.motionClearance});
    cuts.push_back(inside.back().from);
    cuts.push_back(inside.back().to);
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<MotionPiece> pieces;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double from = cuts[k], to = cuts[k + 1];
    if (!(to > from)) continue;
    double required = motionClearance_;
    for (const Interval& zone : inside) {
      if (zone.from <= from && to <= zone.to) required = std::min(required, zone.clearance);
    }
    if (!pieces.empty() && pieces.back().clearance == required) {
      pieces.back().to = to;
    } else {
      pieces.push_back({from, to, required});
    }
  }
  return pieces;
}

double EndpointClearance::stateClearanceAt(const robot::JointRef& q) const {
  double required = clearance_;
  for (const ApproachZone& zone : zones_) {
    if (displacement(zone.endpoint, q) <= kApproachZoneLength) required = std::min(required, zone.stateClearance);
  }
  return required;
}

double EndpointClearance::motionClearanceAlong(const robot::JointRef& qa, const robot::JointRef& qb) const {
  double required = motionClearance_;
  for (const ApproachZone& zone : zones_) {
    if (zone.motionClearance < required && closestApproach(zone.endpoint, qa, qb) <= kApproachZoneLength)
      required = zone.motionClearance;
  }
  return required;
}

}  // namespace arcplan::collision
