#pragma once
// A TCP path as the joint conversion (cartesian_to_joint.h) and the planner's validation see it: a
// curve of known length parametrised by arc length, made of pieces (lines and circular arcs) that
// meet with a common tangent. Implemented by the thesis' line-with-detours (arc_path.h) and by
// lines through via points with blended corners (blended_path.h).
#include <Eigen/Geometry>
#include <functional>
#include <utility>
#include <vector>

namespace arcplan::planners {

// A point of a sampled TCP path.
struct PathSample {
  double arcLength = 0.0;  // from the start along the path
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  bool junction = false;  // the start, the goal, or a point where two pieces meet
};

class TcpPath {
 public:
  virtual ~TcpPath() = default;
  // Analytic length (m).
  virtual double length() const = 0;
  virtual Eigen::Isometry3d pose(double arcLength) const = 0;
  // Samples no more than `resolution` apart along the path (each piece split evenly), containing
  // every junction exactly and ending exactly at the goal. Throws arcplan::Error if resolution is not
  // positive.
  virtual std::vector<PathSample> sample(double resolution) const = 0;

 protected:
  // The tool orientation: constant when start and goal agree, else slerped over the arc length.
  void setEndOrientations(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal);
  Eigen::Quaterniond orientationAt(double arcLength) const;
  // sample() for a path of pieces given as (start arc length, length): each split into
  // ceil(length / resolution) equal parts, `pointOn(i, fraction)` the position that fraction along piece
  // i; then the goal point exactly (not the last piece's rounded end).
  std::vector<PathSample> sampleEvenly(double resolution, const std::vector<std::pair<double, double>>& pieces,
                                       const std::function<Eigen::Vector3d(std::size_t, double)>& pointOn,
                                       const Eigen::Vector3d& startPoint, const Eigen::Vector3d& goalPoint) const;

 private:
  bool constantOrientation_ = true;
  Eigen::Quaterniond startRotation_ = Eigen::Quaterniond::Identity(), goalRotation_ = Eigen::Quaterniond::Identity();
};

}  // namespace arcplan::planners
