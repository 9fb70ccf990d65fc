#pragma once
// A TCP path as the joint conversion (cartesian_to_joint.h) and the planner's validation see it: a
// curve of known length parametrised by arc length, made of pieces (straight lines and circular
// arcs) that meet with a common tangent. Built by the thesis' line-with-detours (arc_path.h) and by
// lines through via points with blended corners (blended_path.h); both only lay out the pieces.
#include <Eigen/Geometry>
#include <vector>

namespace arcplan::planners {

// A point of a sampled TCP path.
struct PathSample {
  double arcLength = 0.0;  // from the start along the path
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  bool junction = false;  // the start, the goal, or a point where two pieces meet
};

// One piece of a path, parametrised by the distance travelled from its start.
struct PathPiece {
  double startArcLength = 0.0;  // where it begins along the whole path
  double length = 0.0;
  bool isArc = false;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // line: start point; arc: centre
  Eigen::Vector3d axisX = Eigen::Vector3d::Zero();   // line: unit direction; arc: unit, centre -> arc start
  Eigen::Vector3d axisY = Eigen::Vector3d::Zero();   // arc: unit tangent at the arc start
  double radius = 0.0;                               // arc

  Eigen::Vector3d point(double distance) const;
  Eigen::Vector3d tangent(double distance) const;  // unit, in the direction of travel
};

class TcpPath {
public:
  virtual ~TcpPath() = default;
  // Analytic length (m).
  double length() const { return length_; }
  Eigen::Vector3d position(double arcLength) const;  // clamped to the path
  Eigen::Vector3d tangent(double arcLength) const;   // unit; zero for a path of zero length
  // The tool orientation: constant when start and goal agree, else slerped over the arc length.
  Eigen::Quaterniond orientation(double arcLength) const;
  Eigen::Isometry3d pose(double arcLength) const;
  const std::vector<PathPiece>& pieces() const { return pieces_; }
  // Arc lengths of the start, every junction between pieces, and the goal, ascending.
  std::vector<double> junctions() const;
  // Samples no more than `resolution` apart along the path (each piece split into
  // ceil(length / resolution) equal parts), containing every junction exactly and ending exactly at
  // the goal. Throws arcplan::Error if resolution is not positive.
  std::vector<PathSample> sample(double resolution) const;

protected:
  // The end poses (positions and the orientation rule); then the pieces are appended in order.
  TcpPath(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal);
  // Pieces shorter than 1e-12 m are left out.
  void appendLine(const Eigen::Vector3d& from, const Eigen::Vector3d& to);
  // The arc of `radius` about `centre`, starting at centre + radius·towardStart and turning by `sweep`
  // (rad, > 0) from the initial direction `startTangent` (both unit, orthogonal).
  void appendArc(const Eigen::Vector3d& centre, double radius, const Eigen::Vector3d& towardStart,
                 const Eigen::Vector3d& startTangent, double sweep);

private:
  const PathPiece& pieceAt(double arcLength) const;

  Eigen::Vector3d startPoint_, goalPoint_;
  bool constantOrientation_ = true;
  Eigen::Quaterniond startRotation_ = Eigen::Quaterniond::Identity(), goalRotation_ = Eigen::Quaterniond::Identity();
  std::vector<PathPiece> pieces_;
  double length_ = 0.0;
};

}  // namespace arcplan::planners
