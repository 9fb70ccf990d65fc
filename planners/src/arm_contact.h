#pragma once
// Via points for the arm, not the tool: when a link above the tool (the forearm, the elbow, the wrist
// links) meets a body while the TCP's own line is free, the via points around the body as the TCP sees
// it (via_points.h) move the tool round a body it never touches. Seen from the TCP, the link is a set of
// points at offsets from it; if the arm followed the TCP rigidly, the link would clear the body wherever
// the TCP clears the body's Minkowski difference with the link (every hull point minus every link
// offset). So that difference gets the usual candidates (over, beside, under: the planes through the
// leg, every margin), restricted to the planes on the side of the body where the link met it (from the
// body towards the contact point, within 60°), and the route search validates them as it does every
// other (the arm does not move rigidly: the margins and the certified walk take up the difference).
// The IK branch is the start's throughout (postures and walks keep it), so the wrist configuration is
// kept. Internal to the arc planner (via_point_planning.cpp).
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "arcplan/collision/scene.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/ur_inverse_kinematics.h"
#include "via_points.h"

namespace arcplan::planners {

// Where a link met a body, seen from the TCP at that configuration.
struct ArmContact {
  std::string link;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // contact point − TCP position (m)
  Eigen::Vector3d side = Eigen::Vector3d::Zero();    // unit: from the body to the contact point, the way out
  std::vector<Eigen::Vector3d> outline;              // the link's outline points − TCP position (m)
};

// A contact is the arm's (not the tool's) when its point lies farther than this from the TCP (m): the
// flange and the tool within it move with the TCP, and their bodies get the TCP's own candidates.
inline constexpr double kArmContactReach = 0.08;

// Per link of a robot (indexed like RobotModel::links()), points in the link's frame that outline its
// collision geometry: a mesh's vertices (every k-th, about kOutlinePoints), a box's corners, a
// cylinder's end circles, a sphere's centre; the link's origin where it has no geometry or its mesh
// cannot be read. Built once per planner.
inline constexpr std::size_t kOutlinePoints = 48;
using LinkOutlines = std::vector<std::vector<Eigen::Vector3d>>;
LinkOutlines linkOutlines(const robot::RobotModel& robot);

// For each pair (link, body) of `pairs` whose body is in `bodies` and whose link is a link of `robot`:
// the outline point of the link nearest that body at configuration q (nearest the bounding box of the
// body's hull points, then its centre), as an offset from the TCP, and the side of the body it is on
// (from the box's nearest point to it; from the box's centre when it lies inside the box); only
// contacts farther than kArmContactReach from the TCP, one per link.
std::vector<ArmContact> armContacts(const robot::RobotModel& robot, const LinkOutlines& outlines,
                                    const robot::Vector6& q,
                                    const std::vector<std::pair<std::string, std::string>>& pairs,
                                    const std::vector<collision::Obstacle>& bodies);

// The cluster as the TCP sees it when the whole link (its outline relative to the TCP) must clear it:
// the Minkowski difference of its hull and the link, every hull point minus every link point (names
// kept). Where the TCP stays outside it, the link, carried rigidly by the TCP, stays outside the cluster.
ObstacleCluster seenFromTheTcp(const ObstacleCluster& cluster, const std::vector<Eigen::Vector3d>& link);

}  // namespace arcplan::planners
