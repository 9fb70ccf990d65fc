#include "arcplan/planners/tcp_path.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arcplan/common/error.h"

namespace arcplan::planners {

void TcpPath::setEndOrientations(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal) {
  startRotation_ = Eigen::Quaterniond(start.linear()).normalized();
  goalRotation_ = Eigen::Quaterniond(goal.linear()).normalized();
  constantOrientation_ = startRotation_.angularDistance(goalRotation_) < 1e-12;
}

Eigen::Quaterniond TcpPath::orientationAt(double arcLength) const {
  if (constantOrientation_) return startRotation_;
  const double total = length();
  if (total <= 1e-12) return arcLength > 0.0 ? goalRotation_ : startRotation_;
  return startRotation_.slerp(std::clamp(arcLength / total, 0.0, 1.0), goalRotation_);
}

std::vector<PathSample> TcpPath::sampleEvenly(double resolution, const std::vector<std::pair<double, double>>& pieces,
                                              const std::function<Eigen::Vector3d(std::size_t, double)>& pointOn,
                                              const Eigen::Vector3d& startPoint, const Eigen::Vector3d& goalPoint) const {
  if (!std::isfinite(resolution) || resolution <= 0.0) {
    std::ostringstream message;
    message << "path resolution must be a finite number > 0 m (got " << resolution << ")";
    throw Error(message.str());
  }
  std::vector<PathSample> samples;
  const auto add = [&](double arcLength, const Eigen::Vector3d& point, bool junction) {
    PathSample sample;
    sample.arcLength = arcLength;
    sample.pose.linear() = orientationAt(arcLength).toRotationMatrix();
    sample.pose.translation() = point;
    sample.junction = junction;
    samples.push_back(sample);
  };
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto [start, length] = pieces[i];
    const int count = std::max(1, static_cast<int>(std::ceil(length / resolution - 1e-9)));
    for (int k = 0; k < count; ++k) {
      const double fraction = static_cast<double>(k) / count;
      add(start + fraction * length, pointOn(i, fraction), k == 0);
    }
  }
  if (samples.empty()) add(0.0, startPoint, true);
  add(length(), goalPoint, true);
  if (!constantOrientation_) samples.back().pose.linear() = goalRotation_.toRotationMatrix();
  return samples;
}

}  // namespace arcplan::planners
