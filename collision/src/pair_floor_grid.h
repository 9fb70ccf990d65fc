#pragma once
// Floors of a self pair that two joints alone move against each other, per cell of those joints' angles
// (ModelImplementation::PairGroup::floorGrid; built in pair_floors.cpp, docs/collision.md "Pair floors").
//
// The relative pose of such a pair's bodies, so their distance d(θa, θb), depends on the two angles only and repeats
// every turn of each. On a straight motion it shrinks at most by reach_a |Δθa| + reach_b |Δθb| (the motion bounds of
// motion_bounds.cpp, per part pair), so a lower bound of d at a cell's centre less half a cell's worth of that is a
// floor of d in the whole cell. The grid measures a cell when a query first asks for it (a few hull distances) and
// keeps it for every later query, of any thread, and of later models of the same robot (pair_floors.cpp's cache):
// MBM's UR5 has two such pairs 1–1.8 cm apart in every state (base_link – upper_arm_link, forearm_link –
// wrist_2_link), whose spheres always overlap, so without floors every state check asked FCL for both.
// Internal to arcplan::collision: not installed.
#include <atomic>
#include <memory>
#include <vector>

#include "arcplan/collision/collision_model.h"
#include "arcplan/robot/kinematics.h"
#include "parts.h"

namespace arcplan::collision::detail {

class PairFloorGrid {
public:
  // One part pair of the group: the parts (copies: the grid outlives the model that built it), the links they are
  // fixed to, and how fast their distance can shrink per radian of each of the two joints.
  struct PartPair {
    Part first, second;
    int firstLink = -1, secondLink = -1;
    double reachA = 0.0, reachB = 0.0;
  };

  // Cells narrow enough that a part pair's distance changes by at most `cellLoss` within one (kMaxCells per joint).
  PairFloorGrid(std::shared_ptr<const robot::RobotModel> robot, const CollisionModelOptions& options, int jointA,
                int jointB, std::vector<PartPair> parts, double cellLoss);

  int jointA() const { return jointA_; }
  int jointB() const { return jointB_; }
  int cellCount() const { return cellsA_ * cellsB_; }
  double stepA() const { return stepA_; }  // cell width along each joint [rad]
  double stepB() const { return stepB_; }
  // A lower bound of the pair's distance at q (dof joint values; only the two joints matter; −infinity for an angle
  // that is not finite or beyond 1e6 rad). At most kFloorCap:
  // the grid tells whether the pair keeps a self pair's clearance, not how far apart it is. `axes`: the caller's
  // directions per part pair of the group (Workspace::pairAxes), kept from cell to cell: a part pair apart along its
  // last direction by more than the floor so far needs no GJK. The floors do not depend on them.
  double at(const robot::JointRef& q, Eigen::Vector3d* axes) const;
  // Whether the pair stays more than `distance` apart on the whole straight motion qa -> qb: every cell its two angles
  // pass through has a floor above `distance` (false for angles `at` gives no floor).
  bool keepsAlong(const robot::JointRef& qa, const robot::JointRef& qb, double distance, Eigen::Vector3d* axes) const;
  // The cells measured so far (tests).
  int measuredCells() const;

  // Above what any query asks of a self pair (a certified motion's 1.26 mm at most, keptClearance of
  // kSelfClearance); a lower cap skips the GJKs of part pairs farther apart.
  static constexpr double kFloorCap = 0.0025;

private:
  double cellFloor(long a, long b, Eigen::Vector3d* axes) const;  // cell indices of any turn
  float measure(int a, int b, Eigen::Vector3d* axes) const;

  std::shared_ptr<const robot::RobotModel> robot_;
  CollisionModelOptions options_;
  int jointA_, jointB_;
  std::vector<PartPair> parts_;
  int cellsA_ = 1, cellsB_ = 1;
  double stepA_ = 0.0, stepB_ = 0.0;
  std::unique_ptr<std::atomic<float>[]> floors_;  // per cell (a-major), NaN until measured
};

// A lower bound of the distance between two robot parts at the given poses, exact below `cap` (above it, any bound
// that reaches `cap`: the capsules', or the hulls' along `axis`): GJK on convex parts, the hulls' bound on mesh parts,
// the capsules' where neither layer is on. `axis`: the direction GJK found last for this pair, kept (hullGap).
double partPairLowerBound(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
                          const CollisionModelOptions& options, double cap, Eigen::Vector3d& axis);

}  // namespace arcplan::collision::detail
