#include "arcplan/planners/blended_path.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arcplan/common/error.h"

namespace arcplan::planners {
namespace {

constexpr double kMinimumLeg = 1e-3;         // m: closer via points are a caller's mistake
constexpr double kStraightOn = 1e-9;         // rad: a corner this flat needs no arc
constexpr double kLengthTolerance = 1e-12;   // m

}  // namespace

double BlendedPath::turningAngle(const std::vector<Eigen::Vector3d>& points, std::size_t i) {
  const Eigen::Vector3d in = (points[i] - points[i - 1]).normalized(), out = (points[i + 1] - points[i]).normalized();
  return std::acos(std::clamp(in.dot(out), -1.0, 1.0));
}

double BlendedPath::maxBlend(const std::vector<Eigen::Vector3d>& points, std::size_t i) {
  const std::size_t corner = i + 1;  // index into points
  const double in = (points[corner] - points[corner - 1]).norm(), out = (points[corner + 1] - points[corner]).norm();
  const bool firstLeg = corner == 1, lastLeg = corner + 2 == points.size();
  return std::min(firstLeg ? in : 0.5 * in, lastLeg ? out : 0.5 * out);
}

BlendedPath::BlendedPath(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal,
                         std::vector<Eigen::Vector3d> vias, std::vector<double> blends)
    : start_(start), goal_(goal), blends_(std::move(blends)) {
  if (vias.size() != blends_.size()) throw Error("blended path: one blend per via point expected");
  points_.push_back(start.translation());
  points_.insert(points_.end(), vias.begin(), vias.end());
  points_.push_back(goal.translation());
  for (std::size_t k = 0; k + 1 < points_.size(); ++k) {
    if (!vias.empty() && (points_[k + 1] - points_[k]).norm() < kMinimumLeg) {
      std::ostringstream message;
      message << "blended path: points " << k << " and " << k + 1 << " are closer than " << kMinimumLeg << " m";
      throw Error(message.str());
    }
  }
  setEndOrientations(start, goal);

  Eigen::Vector3d lineStart = points_.front();
  for (std::size_t i = 0; i < blends_.size(); ++i) {
    const std::size_t corner = i + 1;
    const double t = blends_[i];
    if (!std::isfinite(t) || t <= 0.0 || t > maxBlend(points_, i) + kLengthTolerance) {
      std::ostringstream message;
      message << "blended path: the blend of via point " << i + 1 << " must be in (0, " << maxBlend(points_, i)
              << "] m, got " << t;
      throw Error(message.str());
    }
    const Eigen::Vector3d& v = points_[corner];
    const Eigen::Vector3d in = (v - points_[corner - 1]).normalized(), out = (points_[corner + 1] - v).normalized();
    const double phi = turningAngle(points_, corner);
    if (phi < kStraightOn) {  // straight on: the lines simply continue
      addLine(lineStart, v);
      blendSpans_.emplace_back(length_, length_);
      lineStart = v;
      continue;
    }
    const Eigen::Vector3d entry = v - t * in, exit = v + t * out;
    addLine(lineStart, entry);
    Piece arc;
    arc.isArc = true;
    arc.startArcLength = length_;
    arc.radius = t / std::tan(0.5 * phi);
    arc.sweep = phi;
    arc.length = arc.radius * phi;
    const Eigen::Vector3d inward = (out - out.dot(in) * in).normalized();  // from the arc start toward the centre
    arc.origin = entry + arc.radius * inward;
    arc.axisX = (entry - arc.origin).normalized();
    arc.axisY = in;
    pieces_.push_back(arc);
    blendSpans_.emplace_back(length_, length_ + arc.length);
    length_ += arc.length;
    lineStart = exit;
  }
  addLine(lineStart, points_.back());
}

void BlendedPath::addLine(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const double length = (to - from).norm();
  if (length <= kLengthTolerance) return;
  Piece piece;
  piece.startArcLength = length_;
  piece.length = length;
  piece.origin = from;
  piece.axisX = (to - from) / length;
  pieces_.push_back(piece);
  length_ += length;
}

const BlendedPath::Piece& BlendedPath::pieceAt(double arcLength) const {
  const auto after = std::upper_bound(pieces_.begin(), pieces_.end(), arcLength,
                                      [](double s, const Piece& piece) { return s < piece.startArcLength; });
  return after == pieces_.begin() ? pieces_.front() : *(after - 1);
}

Eigen::Vector3d BlendedPath::piecePoint(const Piece& piece, double distance) const {
  if (!piece.isArc) return piece.origin + distance * piece.axisX;
  const double angle = distance / piece.radius;
  return piece.origin + piece.radius * (std::cos(angle) * piece.axisX + std::sin(angle) * piece.axisY);
}

Eigen::Vector3d BlendedPath::position(double arcLength) const {
  if (pieces_.empty()) return points_.front();
  const Piece& piece = pieceAt(arcLength);
  return piecePoint(piece, std::clamp(arcLength - piece.startArcLength, 0.0, piece.length));
}

Eigen::Vector3d BlendedPath::tangent(double arcLength) const {
  if (pieces_.empty()) return Eigen::Vector3d::Zero();
  const Piece& piece = pieceAt(arcLength);
  if (!piece.isArc) return piece.axisX;
  const double angle = std::clamp(arcLength - piece.startArcLength, 0.0, piece.length) / piece.radius;
  return -std::sin(angle) * piece.axisX + std::cos(angle) * piece.axisY;
}

Eigen::Isometry3d BlendedPath::pose(double arcLength) const {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.linear() = orientationAt(arcLength).toRotationMatrix();
  result.translation() = position(arcLength);
  return result;
}

std::vector<PathSample> BlendedPath::sample(double resolution) const {
  std::vector<std::pair<double, double>> spans;
  for (const Piece& piece : pieces_) spans.emplace_back(piece.startArcLength, piece.length);
  return sampleEvenly(
      resolution, spans,
      [this](std::size_t i, double fraction) { return piecePoint(pieces_[i], fraction * pieces_[i].length); },
      points_.front(), points_.back());
}

}  // namespace arcplan::planners
