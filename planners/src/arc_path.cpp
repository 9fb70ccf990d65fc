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

ArcPath::ArcPath(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal, std::vector<Detour> detours)
    : start_(start), goal_(goal), detours_(std::move(detours)) {
  const Eigen::Vector3d a = start.translation(), b = goal.translation();
  straightLength_ = (b - a).norm();
  if (straightLength_ > kLengthTolerance) lineDirection_ = (b - a) / straightLength_;
  setEndOrientations(start, goal);

  if (!detours_.empty() && straightLength_ <= kLengthTolerance) {
    throw Error("an arc detour needs distinct start and goal TCP positions (|AB| = 0)");
  }
  double lineStart = 0.0;  // arc length on the straight line where the current straight piece begins
  length_ = 0.0;
  const auto addLine = [&](double from, double to) {
    if (to - from <= kLengthTolerance) return;
    Piece piece;
    piece.startArcLength = length_;
    piece.length = to - from;
    piece.origin = a + from * lineDirection_;
    piece.axisX = lineDirection_;
    pieces_.push_back(piece);
    length_ += piece.length;
  };
  for (std::size_t i = 0; i < detours_.size(); ++i) {
    const Detour& detour = detours_[i];
    const ArcDetourProfile profile = makeArcDetourProfile(detour.shape);
    std::ostringstream where;
    where << "detour " << i + 1 << " (O at " << detour.position << " m from A along A->B, |AB| = " << straightLength_
          << " m)";
    if (!std::isfinite(detour.position) || !std::isfinite(detour.planeAngle)) {
      throw Error(where.str() + ": position and plane_angle must be finite numbers");
    }
    const double entry = detour.position - profile.entryOffset;
    const double exit = detour.position + profile.exitOffset;
    if (entry < lineStart - kLengthTolerance) {
      std::ostringstream message;
      message << where.str() << ": the entry arc leaves the line bx2 = " << profile.entryOffset
              << " m before O, but only " << detour.position - lineStart << " m are free before O"
              << (i == 0 ? " (|AO|)" : " (after the previous detour)")
              << "; reduce half_chord, sagitta or entry_radius";
      throw Error(message.str());
    }
    if (exit > straightLength_ + kLengthTolerance) {
      std::ostringstream message;
      message << where.str() << ": the exit arc rejoins the line bx3 = " << profile.exitOffset
              << " m after O, but |OB| = " << straightLength_ - detour.position
              << " m; reduce half_chord, sagitta or exit_radius";
      throw Error(message.str());
    }
    addLine(lineStart, entry);
    const Eigen::Vector3d obstaclePoint = a + detour.position * lineDirection_;
    const Eigen::Vector3d away = avoidanceDirection(lineDirection_, detour.planeAngle);
    const double spanStart = length_;
    for (const PlanarArc& arc : profile.arcs) {
      Piece piece;
      piece.startArcLength = length_;
      piece.length = arc.length();
      piece.isArc = true;
      piece.origin = obstaclePoint;
      piece.axisX = lineDirection_;
      piece.axisZ = away;
      piece.arc = arc;
      pieces_.push_back(piece);
      length_ += piece.length;
    }
    detourSpans_.emplace_back(spanStart, length_);
    lineStart = exit;
  }
  addLine(lineStart, straightLength_);
}

const ArcPath::Piece& ArcPath::pieceAt(double arcLength) const {
  const auto after = std::upper_bound(pieces_.begin(), pieces_.end(), arcLength,
                                      [](double s, const Piece& piece) { return s < piece.startArcLength; });
  return after == pieces_.begin() ? pieces_.front() : *(after - 1);
}

Eigen::Vector3d ArcPath::piecePoint(const Piece& piece, double fraction) const {
  if (!piece.isArc) return piece.origin + (fraction * piece.length) * piece.axisX;
  const Eigen::Vector2d planar = piece.arc.point(fraction);
  return piece.origin + planar.x() * piece.axisX + planar.y() * piece.axisZ;
}

Eigen::Vector3d ArcPath::position(double arcLength) const {
  if (pieces_.empty()) return start_.translation();
  const Piece& piece = pieceAt(arcLength);
  const double fraction = std::clamp((arcLength - piece.startArcLength) / piece.length, 0.0, 1.0);
  return piecePoint(piece, fraction);
}

Eigen::Vector3d ArcPath::tangent(double arcLength) const {
  if (pieces_.empty()) return lineDirection_;
  const Piece& piece = pieceAt(arcLength);
  if (!piece.isArc) return piece.axisX;
  const double fraction = std::clamp((arcLength - piece.startArcLength) / piece.length, 0.0, 1.0);
  const Eigen::Vector2d planar = piece.arc.tangent(fraction);
  return planar.x() * piece.axisX + planar.y() * piece.axisZ;
}

Eigen::Quaterniond ArcPath::orientation(double arcLength) const { return orientationAt(arcLength); }

Eigen::Isometry3d ArcPath::pose(double arcLength) const {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.linear() = orientation(arcLength).toRotationMatrix();
  result.translation() = position(arcLength);
  return result;
}

std::vector<double> ArcPath::junctions() const {
  std::vector<double> result;
  for (const Piece& piece : pieces_) result.push_back(piece.startArcLength);
  result.push_back(length_);
  return result;
}

std::vector<PathSample> ArcPath::sample(double resolution) const {
  std::vector<std::pair<double, double>> spans;
  for (const Piece& piece : pieces_) spans.emplace_back(piece.startArcLength, piece.length);
  return sampleEvenly(
      resolution, spans, [this](std::size_t i, double fraction) { return piecePoint(pieces_[i], fraction); },
      start_.translation(), goal_.translation());
}

}  // namespace arcplan::planners
