#pragma once
// The SIMD sphere prefilter in front of FCL (docs/collision.md, "Sphere prefilter"): the robot's
// sphere model (sphere_model.h) and the obstacles' bounding volumes as float tables, the float
// rounding margin, and the kernels (sphere_kernel.h) chosen at run time: AVX2 where the CPU has it,
// the portable path otherwise; both take the same decisions. The prefilter only ever says "free"
// (every sphere clear of every checked obstacle and sphere by more than the margin) or "ask FCL";
// with spheres that contain the geometry that keeps every answer exactly FCL's.
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "arcplan/robot/kinematics.h"
#include "sphere_model.h"
#include "sphere_tables.h"

namespace arcplan::collision::detail {

// Per-thread scratch of the prefilter queries (part of CollisionData's workspace).
struct SphereWorkspace {
  std::vector<float> q;            // dof × kLanes, joint-major
  std::vector<double> laneStates;  // kLanes × dof, state-major: a batch's states before loadLanes
  std::vector<float> gaps;         // pairs × kLanes
  std::vector<float> enough;       // per pair
  // Batched motion checks (sphere_motion_check.cpp): per pair its motion bound (and the one covered() asks of it),
  // sample fractions, per sample and pair its room (sphere gap less the distance kept), and the work list of intervals.
  std::vector<double> rates, coveredRates, samples, rooms;
  std::vector<char> floored;   // per pair: its floor (PairGroup::floor) keeps the motion's clearance everywhere
  std::vector<char> deferred;  // per pair: one the spheres left to the certified check (PairsLeft)
  std::vector<char> skip;      // per pair: not asked of FCL (unclearedPairsCollide)
  std::vector<std::pair<float, int>> uncleared;  // unclearedPairsCollide's pairs to ask FCL: gap, pair
  std::vector<std::pair<int, int>> intervals, next;
  std::vector<int> pending;
};

class SpherePrefilter {
public:
  SpherePrefilter(const robot::RobotModel& robot, const ModelImplementation& impl,
                  const std::vector<std::string>& linkNames);

  // false for a robot beyond the kernels' fixed limits (sphere_tables.h): every query goes to FCL.
  bool usable() const { return usable_; }
  bool usesAvx2() const { return avx2_; }
  const prefilter::Tables& tables() const { return tables_; }
  const SphereModel& spheres() const { return *spheres_; }
  // Bound of the float error of a sphere centre in the world frame [m] (tests compare it with the
  // measured error), and the margin the kernels require beyond it (sphere_prefilter.cpp).
  double centreErrorBound() const { return centreErrorBound_; }
  double margin() const { return tables_.margin; }
  // Pairs of gaps(): one per body (against its obstacles), then the self pairs: those of
  // ModelImplementation::selfGroups except the rigid ones that never touch, in that order.
  int pairCount() const { return tables_.bodyCount + tables_.selfPairCount; }
  // Self pair p of the tables -> its index in selfGroups, and back (-1: not in the tables).
  int selfGroupOf(int p) const { return selfGroupsOfPairs_[p]; }
  int kernelPairOf(int selfGroup) const { return kernelPairs_[selfGroup]; }
  // The pair of gaps() whose gap bounds group k of impl.groups (obstacle groups: their robot body's, self groups:
  // kernelPairOf's), -1 for a self group left out of the tables.
  int gapPairOfGroup(const ModelImplementation& impl, std::size_t k) const;
  int dof() const { return tables_.dof; }

  void prepare(SphereWorkspace& workspace) const;
  // Puts joint vector `joints` (dof values) into lane `lane` of workspace.q. Defined here: called per
  // state, through the shared library's PLT it cost 9 % of a free-space batch.
  void loadLane(SphereWorkspace& workspace, int lane, const double* joints) const {
    for (int j = 0; j < tables_.dof; ++j) {
      double angle = joints[j];
      if (!(std::abs(angle) <= prefilter::kLargestAngle))
        angle -= prefilter::kLargestAngle * std::nearbyint(angle / prefilter::kLargestAngle);
      workspace.q[static_cast<std::size_t>(j * prefilter::kLanes + lane)] = static_cast<float>(angle);
    }
  }
  // Puts `lanes` states (dof values each, state k at states + k * stride) into the lanes, the other
  // lanes repeating the first: the same floats as loadLane for each.
  void loadLanes(SphereWorkspace& workspace, const double* states, std::ptrdiff_t stride, int lanes) const;
  // Lanes (bit k) of the first `lanes` loaded states that the spheres prove free.
  std::uint32_t freeLanes(SphereWorkspace& workspace, int lanes) const;
  // workspace.gaps for all kLanes loaded lanes (workspace.enough set per pair).
  void gaps(SphereWorkspace& workspace) const;

private:
  bool usable_ = false, avx2_ = false;
  std::shared_ptr<const SphereModel> spheres_;
  std::vector<prefilter::LinkRow> links_;
  std::vector<prefilter::BodyRow> bodies_;
  std::vector<float> fineX_, fineY_, fineZ_, fineR_;
  std::vector<prefilter::GroupRow> groups_;
  std::vector<prefilter::ObstacleRow> obstacles_;
  std::vector<int> obstacleIndex_, selfPairs_, selfGroupsOfPairs_, kernelPairs_;
  prefilter::Tables tables_;
  double centreErrorBound_ = 0.0;
};

// Whether the spheres prove q free (false: FCL decides). q must have robot().dof() values.
bool sphereFree(const SpherePrefilter& prefilter, SphereWorkspace& workspace, const robot::JointRef& q);

// What the spheres tell about a straight motion qa -> qb (sphere_motion_check.cpp); PairsLeft only when
// deferPairs (else such a motion is Unknown).
enum class SphereMotion {
  Free,      // every pair keeps more than m + acceptanceMargin(m) all along: the certified check accepts it too
  Collides,  // a state on it collides (FCL said so): the certified check rejects it too
  Unknown,   // the certified check decides
  // Every pair keeps more than m + acceptanceMargin(m) all along except those marked in SphereWorkspace::deferred
  // (a body against its obstacles, a self pair), whose spheres came too close somewhere: the certified check need
  // only follow those (for a body, its obstacle groups).
  PairsLeft
};
SphereMotion sphereMotion(const CollisionModel& model, Workspace& data, const robot::JointRef& qa,
                          const robot::JointRef& qb, double minimumClearance, bool deferPairs);

// isCollisionFree without the prefilter (collision_model.cpp).
bool exactlyCollisionFree(const CollisionModel& model, Workspace& data, const robot::JointRef& q);
// Whether q, in lane `lane` of the last SpherePrefilter::gaps(), collides: FCL asked for the pairs whose sphere gap
// there is not positive (q placed by updateRobot when one is), but not those with skip[p] set (none when skip is null)
// nor the self pairs whose floor grid proves them apart; the others are apart (the spheres contain the geometry, the
// gaps are less the float margin), so with none skipped this is exactlyCollisionFree's answer (collision_model.cpp).
bool unclearedPairsCollide(const CollisionModel& model, Workspace& data, const robot::JointRef& q, int lane,
                           const char* skip = nullptr);
// workspace.gaps of the loaded lanes, fine enough to tell for every pair whether it is apart (gap > 0).
void collisionGaps(const SpherePrefilter& prefilter, SphereWorkspace& workspace);

}  // namespace arcplan::collision::detail
