#include "arcplan/planners/tcp_path.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arcplan/common/error.h"

namespace arcplan::planners {
namespace {

// Below this a length counts as zero (m): far under any resolution a robot can execute.
constexpr double kLengthTolerance = 1e-12;

}  // namespace

Eigen::Vector3d PathPiece::point(double distance) const {
  if (!isArc) return origin + distance * axisX;
  const double angle = distance / radius;
  return origin + radius * (std::cos(angle) * axisX + std::sin(angle) * axisY);
}

Eigen::Vector3d PathPiece::tangent(double distance) const {
  if (!isArc) return axisX;
  const double angle = distance / radius;
  return -std::sin(angle) * axisX + std::cos(angle) * axisY;
}

TcpPath::TcpPath(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal)
    : startPoint_(start.translation()), goalPoint_(goal.translation()) {
  startRotation_ = Eigen::Quaterniond(start.linear()).normalized();
  goalRotation_ = Eigen::Quaterniond(goal.linear()).normalized();
  constantOrientation_ = startRotation_.angularDistance(goalRotation_) < 1e-12;
}

void TcpPath::appendLine(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const double distance = (to - from).norm();
  if (distance <= kLengthTolerance) return;
  PathPiece piece;
  piece.startArcLength = length_;
  piece.length = distance;
  piece.origin = from;
  piece.axisX = (to - from) / distance;
  pieces_.push_back(piece);
  length_ += distance;
}

void TcpPath::appendArc(const Eigen::Vector3d& centre, double radius, const Eigen::Vector3d& towardStart,
                        const Eigen::Vector3d& startTangent, double sweep) {
  PathPiece piece;
  piece.isArc = true;
  piece.startArcLength = length_;
  piece.origin = centre;
  piece.radius = radius;
  piece.axisX = towardStart;
  piece.axisY = startTangent;
  piece.length = radius * sweep;
  pieces_.push_back(piece);
  length_ += piece.length;
}

const PathPiece& TcpPath::pieceAt(double arcLength) const {
  const auto after = std::upper_bound(pieces_.begin(), pieces_.end(), arcLength,
                                      [](double s, const PathPiece& piece) { return s < piece.startArcLength; });
  return after == pieces_.begin() ? pieces_.front() : *(after - 1);
}

Eigen::Vector3d TcpPath::position(double arcLength) const {
  if (pieces_.empty()) return startPoint_;
  const PathPiece& piece = pieceAt(arcLength);
  return piece.point(std::clamp(arcLength - piece.startArcLength, 0.0, piece.length));
}

Eigen::Vector3d TcpPath::tangent(double arcLength) const {
  if (pieces_.empty()) return Eigen::Vector3d::Zero();
  const PathPiece& piece = pieceAt(arcLength);
  return piece.tangent(std::clamp(arcLength - piece.startArcLength, 0.0, piece.length));
}

Eigen::Quaterniond TcpPath::orientation(double arcLength) const {
  if (constantOrientation_) return startRotation_;
  if (length_ <= kLengthTolerance) return arcLength > 0.0 ? goalRotation_ : startRotation_;
  return startRotation_.slerp(std::clamp(arcLength / length_, 0.0, 1.0), goalRotation_);
}

Eigen::Isometry3d TcpPath::pose(double arcLength) const {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.linear() = orientation(arcLength).toRotationMatrix();
  result.translation() = position(arcLength);
  return result;
}

std::vector<double> TcpPath::junctions() const {
  std::vector<double> result;
  for (const PathPiece& piece : pieces_) result.push_back(piece.startArcLength);
  result.push_back(length_);
  return result;
}

std::vector<PathSample> TcpPath::sample(double resolution) const {
  if (!std::isfinite(resolution) || resolution <= 0.0) {
    std::ostringstream message;
    message << "path resolution must be a finite number > 0 m (got " << resolution << ")";
    throw Error(message.str());
  }
  std::vector<PathSample> samples;
  const auto add = [&](double arcLength, const Eigen::Vector3d& point, bool junction) {
    PathSample sample;
    sample.arcLength = arcLength;
    sample.pose.linear() = orientation(arcLength).toRotationMatrix();
    sample.pose.translation() = point;
    sample.junction = junction;
    samples.push_back(sample);
  };
  for (const PathPiece& piece : pieces_) {
    const int count = std::max(1, static_cast<int>(std::ceil(piece.length / resolution - 1e-9)));
    for (int k = 0; k < count; ++k) {
      const double fraction = static_cast<double>(k) / count;
      add(piece.startArcLength + fraction * piece.length, piece.point(fraction * piece.length), k == 0);
    }
  }
  if (samples.empty()) add(0.0, startPoint_, true);
  add(length_, goalPoint_, true);
  if (!constantOrientation_) samples.back().pose.linear() = goalRotation_.toRotationMatrix();
  return samples;
}

}  // namespace arcplan::planners
