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
#include <functional>
#include <optional>
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

// The Minkowski difference treats the arm as rigid; it is not (the elbow drops as the TCP reaches out,
// rises as it comes in), so a link crossing a long body — a forearm under a beam — may need the TCP
// far from where the difference puts it. Detours measured on the arm itself: `clear` says whether the
// arm, in the posture the IK gives for a TCP position (the branch and tool orientation kept), keeps
// the margin there; one IK solution and one clearance test each, far cheaper than a certified walk.
using PostureClear = std::function<bool(const Eigen::Vector3d&)>;

// Distance (m) between the postures probed along a leg and across it.
inline constexpr double kPostureProbeStep = 0.02;

// The stretch of the leg p -> q (distances from p, m) around `at` whose postures fail `clear`, probed
// every kPostureProbeStep: both ends at `at` when its own posture is clear.
struct BlockedSpan {
  double from = 0.0, to = 0.0;
};
BlockedSpan blockedSpan(const Eigen::Vector3d& p, const Eigen::Vector3d& q, double at, const PostureClear& clear);

// Per plane through the leg (the directions of viaCandidates), the smallest lift of kDetourLifts that
// clears the span: two via points that far across the leg, entering and leaving as far along it as
// the lift (45° ramps, kept within the leg), every posture probed along p -> via -> via -> q clear (the
// span's first, where a lift too small fails soonest). Its margin is the lift's step from the one below,
// which route shortening may take back. Nothing in a plane where no lift clears.
inline constexpr double kDetourLifts[] = {0.03, 0.06, 0.1, 0.15, 0.2, 0.27, 0.35, 0.45};
std::vector<ViaCandidate> clearingDetours(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const BlockedSpan& span,
                                          const PostureClear& clear);

// When no such detour clears — the arm must pass a long body low, or reach the end from another
// side — a search of TCP positions on a lattice of kLatticeStep about p (weighted A*, 26 neighbours, path length
// as cost, kLatticeGreed × the straight-line distance to q as heuristic; a lattice point is passable where `clear`
// holds, at most kLatticeTests tested) for a way from p to q, then cut short greedily (a via point is kept only where
// the straight leg past it would not be clear at every kPostureProbeStep). The via points between p and q when there
// are at most `maxViaPoints`; nothing otherwise.
inline constexpr double kLatticeStep = 0.04;
inline constexpr int kLatticeTests = 20000;
// A heuristic weighted above 1 finds a way with fewer posture tests (~4 µs each), at most this factor longer on the
// lattice, before the greedy cut: on forearm-beam-003/-008/-011 1.5 took 28–40 % fewer tests and the paths executed
// within 0.03 % of the unweighted ones' times (2: up to 0.8 % slower).
inline constexpr double kLatticeGreed = 1.5;
std::optional<ViaCandidate> latticeDetour(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const PostureClear& clear,
                                          std::size_t maxViaPoints);

}  // namespace arcplan::planners
