#include "arcplan/planners/blended_path.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arcplan/common/error.h"

namespace arcplan::planners {
namespace {

constexpr double kMinimumLeg = 1e-3;        // m: closer via points are a caller's mistake
constexpr double kStraightOn = 1e-9;        // rad: a corner this flat needs no arc
constexpr double kLengthTolerance = 1e-12;  // m

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
    : TcpPath(start, goal), blends_(std::move(blends)) {
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
      appendLine(lineStart, v);
      blendSpans_.emplace_back(length(), length());
      lineStart = v;
      continue;
    }
    const Eigen::Vector3d entry = v - t * in, exit = v + t * out;
    appendLine(lineStart, entry);
    const double radius = t / std::tan(0.5 * phi);
    const Eigen::Vector3d inward = (out - out.dot(in) * in).normalized();  // from the arc start toward the centre
    const double blendStart = length();
    appendArc(entry + radius * inward, radius, -inward, in, phi);
    blendSpans_.emplace_back(blendStart, length());
    lineStart = exit;
  }
  appendLine(lineStart, points_.back());
}

}  // namespace arcplan::planners
