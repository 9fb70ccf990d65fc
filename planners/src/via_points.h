#pragma once
// Via-point candidates from the obstacles' geometry, for the via-point search (route_search.h).
//
// Obstacles are grouped into clusters: bodies whose bounding boxes come closer than `gap` are one
// cluster (a shelf's panels, a box on a box), since the robot cannot pass between them. Bodies lying
// below the robot's base plane (the table it stands on) are the floor: never part of a cluster.
// Each cluster is kept as points whose convex hull contains it (box corners, the circumscribed
// octagons of a cylinder's caps, the circumscribed cube of a sphere or mesh ball).
//
// Around a cluster blocking a leg p -> q, candidates lie in planes through the leg, the plane's
// "away" direction d turned about the leg in 30° steps from world up (avoidanceDirection, so 0 is
// "lift over" and ±90° go round the side). With y the hull's largest extent along d and [x0, x1] its
// extent along the leg, a candidate keeps clearance + margin beyond y:
//   - over: two via points at x0 - margin and x1 + margin (a trapezoid, for walls and wide bodies);
//   - apex: one via point above the cluster's middle, high enough that both straight legs clear
//     every hull point by clearance + margin (a triangle, the shortest way past a small body).
// Margins grow from 2 cm to 35 cm: the tool and the arm above it need room besides the clearance.
#include <Eigen/Core>
#include <boost/container/small_vector.hpp>
#include <optional>
#include <string>
#include <vector>

#include "arcplan/collision/scene.h"

namespace arcplan::planners {

struct ObstacleCluster {
  std::vector<std::string> names;
  std::vector<Eigen::Vector3d> hull;  // points whose convex hull contains every body of the cluster
};

// Points whose convex hull contains the obstacle.
std::vector<Eigen::Vector3d> hullPoints(const collision::Obstacle& obstacle);

// Clusters of the obstacles that are not floor, in the order of their first body.
std::vector<ObstacleCluster> clusterObstacles(const std::vector<collision::Obstacle>& obstacles, double gap);

// A way past a cluster: one or two via points between p and q (a lattice detour: up to 10), with the margin they keep.
// The points held in place up to two: a failed leg makes up to 120 candidates, most never walked, and a heap block for
// each was most of their cost.
struct ViaCandidate {
  boost::container::small_vector<Eigen::Vector3d, 2> points;
  double margin = 0.0;  // m beyond clearance
};

// Candidates (over and apex, every plane and margin) around `cluster` for the leg p -> q. Points
// closer than 1 cm to p or q along the leg are moved inward; candidates needing an apex higher than
// 1.5 m are left out. With `side`, only the planes whose "away" direction lies within 60° of side's
// part across the leg (the side of the cluster something should pass on; all planes when side runs
// along the leg).
std::vector<ViaCandidate> viaCandidates(const ObstacleCluster& cluster, const Eigen::Vector3d& p,
                                        const Eigen::Vector3d& q, double clearance,
                                        const std::optional<Eigen::Vector3d>& side = std::nullopt);

}  // namespace arcplan::planners
