#pragma once
// The thesis' arc detour (seed chapter 3.4, Table 3.1; geometry in docs/planners.md) and the TCP path
// it makes along a segment A→B.
//
// 2D: in the avoidance plane, origin at the obstacle point O on the line, x along A→B, z away from
// the obstacle side. The straight line is left at (-bx2, 0) on an entry arc (radius R2), continues
// on the main arc (radius Rs, apex (0, h) above O) and returns to the line at (bx3, 0) on an exit
// arc (radius R3). Consecutive pieces share their end point and unit tangent (C¹ at constant speed).
//
// 3D: the plane contains A→B and the "away" direction: world up made orthogonal to A→B, rotated
// about A→B by `planeAngle` (right hand). When A→B is vertical, world x takes the role of up.
// The tool orientation is constant when start and goal agree, else slerped over the arc length.
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "arcplan/planners/tcp_path.h"

namespace arcplan::planners {

// Shape of one detour (m). Thesis example: h = 0.5·r, r = 0.2, R2 = 0.5·r, R3 = r.
struct ArcParameters {
  double sagitta = 0.1;      // h: height of the main arc's apex above O, 0 < h <= r
  double halfChord = 0.2;    // r
  double entryRadius = 0.1;  // R2, the arc nearer to A
  double exitRadius = 0.2;   // R3, the arc nearer to B
};

// What is wrong with the shape, naming the parameter and the valid range (all finite, 0 < h <= r,
// R2, R3 > 0); empty when it is valid.
std::string arcParametersProblem(const ArcParameters& parameters);
// Throws arcplan::Error with arcParametersProblem's text for an invalid shape.
void validateArcParameters(const ArcParameters& parameters);

// A circular arc in a plane: the point at angle t is center + radius·(cos t, sin t).
struct PlanarArc {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
  double startAngle = 0.0;
  double sweep = 0.0;  // signed: > 0 counter-clockwise (toward +z from +x)

  double length() const;
  Eigen::Vector2d point(double fraction) const;    // fraction of the arc in [0, 1]
  Eigen::Vector2d tangent(double fraction) const;  // unit, in the direction of travel
};

// Table 3.1 for one parameter set.
struct ArcDetourProfile {
  ArcParameters parameters;
  double mainRadius = 0.0;        // Rs = (h² + r²) / (2h)
  double mainCenterDepth = 0.0;   // zs = Rs - h: the main arc's centre is (0, -zs)
  double entryOffset = 0.0;       // bx2: the detour leaves the line at (-bx2, 0)
  double exitOffset = 0.0;        // bx3: it rejoins the line at (bx3, 0)
  double entryAngle = 0.0;        // β2
  double exitAngle = 0.0;         // β3
  std::array<PlanarArc, 3> arcs;  // in travel order: entry (arc 2), main (arc 1), exit (arc 3)

  // R2·β2 + Rs·(β2 + β3) + R3·β3.
  double arcLength() const;
  // How much longer the detour is than the straight piece it replaces: arcLength() - (bx2 + bx3).
  double extraLength() const;
};

// Validates and evaluates Table 3.1 (zs = Rs - h makes the circles tangent).
ArcDetourProfile makeArcDetourProfile(const ArcParameters& parameters);

// One detour on the line A→B.
struct Detour {
  double position = 0.0;  // distance of O from A along A→B (m)
  ArcParameters shape;
  double planeAngle = 0.0;  // rad, rotation of the away direction about A→B
};

// Unit "away" direction of the avoidance plane, orthogonal to the unit line direction.
Eigen::Vector3d avoidanceDirection(const Eigen::Vector3d& lineDirection, double planeAngle);

// What is wrong with placing `detours` on the line start→goal, naming the detour and what to change:
// an invalid shape, detours out of order or overlapping, not fitting between A and B (bx2 <= |AO|,
// bx3 <= |OB|), or detours on a zero-length line; empty when ArcPath accepts them.
std::string detoursProblem(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal,
                           const std::vector<Detour>& detours);

// The TCP path from start to goal: the straight line with the given detours (none: a LIN move).
class ArcPath : public TcpPath {
public:
  // Throws arcplan::Error with detoursProblem's text for detours it does not accept. Its length() is
  // |AB| + the extra length of every detour.
  ArcPath(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal, std::vector<Detour> detours = {});

  const Eigen::Isometry3d& start() const { return start_; }
  const Eigen::Isometry3d& goal() const { return goal_; }
  const std::vector<Detour>& detours() const { return detours_; }
  // Unit A→B (zero vector when A = B).
  const Eigen::Vector3d& lineDirection() const { return lineDirection_; }
  double straightLength() const { return straightLength_; }
  // Arc lengths where detour i leaves the line and where it rejoins it.
  std::pair<double, double> detourSpan(std::size_t i) const { return detourSpans_.at(i); }

private:
  Eigen::Isometry3d start_, goal_;
  std::vector<Detour> detours_;
  Eigen::Vector3d lineDirection_ = Eigen::Vector3d::Zero();
  double straightLength_ = 0.0;
  std::vector<std::pair<double, double>> detourSpans_;
};

}  // namespace arcplan::planners
