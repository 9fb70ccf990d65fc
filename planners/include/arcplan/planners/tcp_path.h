#pragma once
// A TCP path as the joint conversion (cartesian_to_joint.h) and the planner's validation see it: a
// curve of known length parametrised by arc length, made of pieces (lines and circular arcs) that
// meet with a common tangent. Implemented by the thesis' line-with-detours (arc_path.h) and by
// lines through via points with blended corners (blended_path.h).
#include <Eigen/Geometry>
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
};

}  // namespace arcplan::planners
