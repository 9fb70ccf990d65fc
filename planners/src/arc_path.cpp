#include "arcplan/planners/arc_path.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arcplan/common/error.h"

namespace arcplan::planners {
namespace {

// Below this a length counts as zero (m): far under any resolution a robot can execute.
constexpr double kLengthTolerance = 1e-12;

std::string notPositive(double value, const char* name) {
  if (std::isfinite(value) && value > 0.0) return {};
  std::ostringstream message;
  message << "arc parameter " << name << " must be a finite number > 0 (got " << value << ")";
  return message.str();
}

}  // namespace

std::string arcParametersProblem(const ArcParameters& p) {
  for (const std::string& problem :
       {notPositive(p.sagitta, "sagitta (h)"), notPositive(p.halfChord, "half_chord (r)"),
        notPositive(p.entryRadius, "entry_radius (R2)"), notPositive(p.exitRadius, "exit_radius (R3)")}) {
    if (!problem.empty()) return problem;
  }
  if (p.sagitta > p.halfChord) {
    std::ostringstream message;
    message << "arc parameter sagitta (h) must satisfy 0 < h <= half_chord (r); got h = " << p.sagitta
            << " m > r = " << p.halfChord << " m";
    return message.str();
  }
  return {};
}

void validateArcParameters(const ArcParameters& p) {
  const std::string problem = arcParametersProblem(p);
  if (!problem.empty()) throw Error(problem);
}

double PlanarArc::length() const { return radius * std::abs(sweep); }

Eigen::Vector2d PlanarArc::point(double fraction) const {
  const double angle = startAngle + fraction * sweep;
  return center + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
}

Eigen::Vector2d PlanarArc::tangent(double fraction) const {
  const double angle = startAngle + fraction * sweep;
  const double direction = sweep >= 0.0 ? 1.0 : -1.0;
  return direction * Eigen::Vector2d(-std::sin(angle), std::cos(angle));
}

double ArcDetourProfile::arcLength() const { return arcs[0].length() + arcs[1].length() + arcs[2].length(); }

double ArcDetourProfile::extraLength() const { return arcLength() - (entryOffset + exitOffset); }

ArcDetourProfile makeArcDetourProfile(const ArcParameters& parameters) {
  validateArcParameters(parameters);
  const double h = parameters.sagitta, r = parameters.halfChord;
  const double r2 = parameters.entryRadius, r3 = parameters.exitRadius;
  ArcDetourProfile profile;
  profile.parameters = parameters;
  profile.mainRadius = (h * h + r * r) / (2.0 * h);
  profile.mainCenterDepth = profile.mainRadius - h;
  const double rs = profile.mainRadius, zs = profile.mainCenterDepth;
  // Side arcs: centre at height R on the line's away side, externally tangent to the main circle.
  const auto sideOffset = [&](double radius) {
    return std::sqrt((radius + rs) * (radius + rs) - (radius + zs) * (radius + zs));
  };
  const auto sideAngle = [&](double radius) { return std::acos(std::clamp((radius + zs) / (radius + rs), -1.0, 1.0)); };
  profile.entryOffset = sideOffset(r2);
  profile.exitOffset = sideOffset(r3);
  profile.entryAngle = sideAngle(r2);
  profile.exitAngle = sideAngle(r3);
  const double b2 = profile.entryAngle, b3 = profile.exitAngle;
  profile.arcs[0] = {Eigen::Vector2d(-profile.entryOffset, r2), r2, -M_PI_2, b2};
  profile.arcs[1] = {Eigen::Vector2d(0.0, -zs), rs, M_PI_2 + b2, -(b2 + b3)};
  profile.arcs[2] = {Eigen::Vector2d(profile.exitOffset, r3), r3, -M_PI_2 - b3, b3};
  return profile;
}

Eigen::Vector3d avoidanceDirection(const Eigen::Vector3d& lineDirection, double planeAngle) {
  // World up, unless the line is (nearly) vertical: then up is no direction across it and world x serves.
  Eigen::Vector3d reference = Eigen::Vector3d::UnitZ();
  if (lineDirection.cross(reference).norm() < 1e-9) reference = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d away = (reference - reference.dot(lineDirection) * lineDirection).normalized();
  return Eigen::AngleAxisd(planeAngle, lineDirection) * away;
}

std::string detoursProblem(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal,
                           const std::vector<Detour>& detours) {
  const double straightLength = (goal.translation() - start.translation()).norm();
  if (!detours.empty() && straightLength <= kLengthTolerance) {
    return "an arc detour needs distinct start and goal TCP positions (|AB| = 0)";
  }
  double lineStart = 0.0;  // arc length on the straight line where the current straight piece begins
  for (std::size_t i = 0; i < detours.size(); ++i) {
    const Detour& detour = detours[i];
    const std::string shapeProblem = arcParametersProblem(detour.shape);
    if (!shapeProblem.empty()) return shapeProblem;
    const ArcDetourProfile profile = makeArcDetourProfile(detour.shape);
    std::ostringstream message;
    message << "detour " << i + 1 << " (O at " << detour.position << " m from A along A->B, |AB| = " << straightLength
            << " m)";
    if (!std::isfinite(detour.position) || !std::isfinite(detour.planeAngle)) {
      return message.str() + ": position and plane_angle must be finite numbers";
    }
    if (detour.position - profile.entryOffset < lineStart - kLengthTolerance) {
      message << ": the entry arc leaves the line bx2 = " << profile.entryOffset << " m before O, but only "
              << detour.position - lineStart << " m are free before O"
              << (i == 0 ? " (|AO|)" : " (after the previous detour)")
              << "; reduce half_chord, sagitta or entry_radius";
      return message.str();
    }
    if (detour.position + profile.exitOffset > straightLength + kLengthTolerance) {
      message << ": the exit arc rejoins the line bx3 = " << profile.exitOffset
              << " m after O, but |OB| = " << straightLength - detour.position
              << " m; reduce half_chord, sagitta or exit_radius";
      return message.str();
    }
    lineStart = detour.position + profile.exitOffset;
  }
  return {};
}

ArcPath::ArcPath(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal, std::vector<Detour> detours)
    : TcpPath(start, goal), start_(start), goal_(goal), detours_(std::move(detours)) {
  const std::string problem = detoursProblem(start, goal, detours_);
  if (!problem.empty()) throw Error(problem);
  const Eigen::Vector3d a = start.translation(), b = goal.translation();
  straightLength_ = (b - a).norm();
  if (straightLength_ > kLengthTolerance) lineDirection_ = (b - a) / straightLength_;
  double lineStart = 0.0;  // arc length on the straight line where the current straight piece begins
  const auto addLine = [&](double from, double to) {
    if (to - from > kLengthTolerance) appendLine(a + from * lineDirection_, a + to * lineDirection_);
  };
  for (const Detour& detour : detours_) {
    const ArcDetourProfile profile = makeArcDetourProfile(detour.shape);
    addLine(lineStart, detour.position - profile.entryOffset);
    const Eigen::Vector3d obstaclePoint = a + detour.position * lineDirection_;
    const Eigen::Vector3d away = avoidanceDirection(lineDirection_, detour.planeAngle);
    const double spanStart = length();
    // The avoidance plane's coordinates (x along A→B, z away) in 3D.
    const auto inSpace = [&](const Eigen::Vector2d& planar) { return planar.x() * lineDirection_ + planar.y() * away; };
    for (const PlanarArc& arc : profile.arcs) {
      const Eigen::Vector2d radial(std::cos(arc.startAngle), std::sin(arc.startAngle));
      appendArc(obstaclePoint + inSpace(arc.center), arc.radius, inSpace(radial), inSpace(arc.tangent(0.0)),
                std::abs(arc.sweep));
    }
    detourSpans_.emplace_back(spanStart, length());
    lineStart = detour.position + profile.exitOffset;
  }
  addLine(lineStart, straightLength_);
}

}  // namespace arcplan::planners
