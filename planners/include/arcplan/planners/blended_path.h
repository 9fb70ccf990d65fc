#pragma once
// Straight TCP lines through via points whose corners are rounded by circular arcs tangent to both
// lines (C¹ at constant speed, like a robot controller's blend radius). A corner with tangent length
// t and turning angle φ gets an arc of radius t / tan(φ/2) that leaves the incoming line t before
// the via point and joins the outgoing line t after it; its midpoint passes t·tan(φ/4) inside the
// corner. The tool orientation is constant when start and goal agree, else slerped over the arc length.
#include <Eigen/Geometry>
#include <vector>

#include "arcplan/planners/tcp_path.h"

namespace arcplan::planners {

class BlendedPath : public TcpPath {
public:
  // `vias` between the start's and the goal's positions; `blends[i]` is the tangent length of the
  // corner at vias[i] (m, > 0 and at most maxBlend(i)). Throws arcplan::Error for mismatched sizes,
  // consecutive points closer than 1 mm, non-positive blends or blends that overlap.
  BlendedPath(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal, std::vector<Eigen::Vector3d> vias,
              std::vector<double> blends);

  // The largest tangent length the corner at vias[i] can have: the whole of a leg that ends at the
  // start or goal, half of a leg shared with another corner.
  static double maxBlend(const std::vector<Eigen::Vector3d>& points, std::size_t i);
  // Turning angle (rad) of the corner at points[i] (0 = straight on).
  static double turningAngle(const std::vector<Eigen::Vector3d>& points, std::size_t i);

  // Start, vias and goal positions.
  const std::vector<Eigen::Vector3d>& points() const { return points_; }
  const std::vector<double>& blends() const { return blends_; }
  // Arc lengths where the blend of corner i begins and ends (equal for a straight-on corner).
  std::pair<double, double> blendSpan(std::size_t i) const { return blendSpans_.at(i); }

private:
  std::vector<Eigen::Vector3d> points_;
  std::vector<double> blends_;
  std::vector<std::pair<double, double>> blendSpans_;
};

}  // namespace arcplan::planners
