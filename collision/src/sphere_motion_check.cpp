// Batched, certified motion checks through the sphere prefilter (sphere_prefilter.h): the
// certificate of motion_check.cpp with states evaluated 8 at a time, coarse to fine.
//
// On the motion q(s) = qa + s (qb − qa) a pair whose geometry is at least g_i apart at s_i stays more
// than `kept` apart for |s − s_i| <= (g_i − kept) / rate, kept = keptClearance(the pair's own m:
// requiredDistance of minimumClearance, collision_model.h),
// rate being the motion bound of motion_check.h (how fast the pair's distance can shrink per unit of
// s). The spheres give g (their gaps, less the float margin) for 8 states per kernel call. An interval
// between two samples is covered for a pair when its rooms there, g − kept, reach its motion bound over the
// interval: room_i + room_j >= rate (s_j − s_i) (compared so, without a division per pair and sample, which took
// 11 % of a short motion's check); the motion is free when every
// interval is covered for every pair. Uncovered intervals get new samples inside them, 8 per batch
// spread over them, until all are covered or kMaxSamples are spent. A pair whose spheres come too close
// somewhere is deferred: the rake goes on certifying every other pair, and the exact check then follows
// the deferred pairs alone (SphereMotion::PairsLeft). For a body's obstacle pair the closest such state
// is first checked by FCL (a collision rejects the motion), and before the exact check takes over the
// motion is searched for a collision of the deferred bodies (evenly spaced states, coarse first, a few
// FCL checks at most). Self pairs that are close in every state (on MBM's UR5 base_link – upper_arm_link
// and forearm_link – wrist_2_link, 1–1.8 cm apart, their spheres always overlapping) would otherwise keep
// the spheres from certifying any motion of such a robot; a gripper sliding past a shelf's board made
// the exact check follow all ~400 pair groups of MBM's UR5 scenes where it needs the gripper's few
// (20 bookshelf, box and table problems: such motions 0.50 ms each, 380 of the 680 ms of RRTConnect +
// simplifier's motion checks). Where the last valid state is wanted nothing is deferred: a state whose
// spheres come too close then blocks the rake, the motion is only searched for a collision and the
// exact check follows every pair.
#include <algorithm>
#include <cmath>
#include <limits>

#include "model_implementation.h"
#include "motion_clearance.h"
#include "pair_floor_grid.h"
#include "sphere_prefilter.h"

namespace arcplan::collision::detail {
namespace {

using prefilter::kLanes;

// Samples before the exact check takes over (a motion grazing an obstacle would need many).
constexpr int kMaxSamples = 256;
// Searching a motion the spheres cannot certify: states at most this far apart (largest joint
// change, rad), and at most this many FCL checks of states the spheres do not clear.
constexpr double kSearchStep = 0.02;
constexpr int kMaxExactChecks = 4;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Rake {
  const CollisionModel& model;
  const SpherePrefilter& prefilter;
  Workspace& data;
  SphereWorkspace& work;
  const robot::JointRef& qa;
  const robot::JointRef& qb;
  double keptObstacle, keptSelf;  // keptClearance of the motion's m for the bodies' obstacle pairs, the self pairs
  int bodies, pairs;
  bool deferring;          // pairs too close for the spheres are deferred (PairsLeft), not blocking
  bool blocked = false;    // (not deferring) a free state too close for the spheres: they cannot certify the motion
  bool searching = false;  // search(): only the closest states of the pairs left open go to FCL
  int exactChecks = 0;

  // Evaluates work.pending (sample indices, spacing h to their neighbours): Collides if FCL finds a
  // state in collision, else Free (meaning: go on).
  SphereMotion evaluate(double h) {
    for (std::size_t first = 0; first < work.pending.size(); first += kLanes) {
      const int lanes = static_cast<int>(std::min<std::size_t>(kLanes, work.pending.size() - first));
      const int dof = prefilter.dof();
      double* states = work.laneStates.data();
      for (int lane = 0; lane < kLanes; ++lane) {
        const double s = work.samples[work.pending[first + std::min(lane, lanes - 1)]];
        for (int j = 0; j < dof; ++j) states[lane * dof + j] = qa[j] + s * (qb[j] - qa[j]);
      }
      prefilter.loadLanes(work, states, dof, kLanes);
      for (int p = 0; p < pairs; ++p)
        work.enough[p] =
            skipped(p) ? -prefilter::kFarGap : static_cast<float>(kept(p) + work.rates[p] * h + prefilter.margin());
      prefilter.gaps(work);
      // Of the states the spheres do not clear, the closest (the likeliest collision) goes to FCL.
      int closest = -1, closestLane = 0;
      double closestGap = kInfinity;
      for (int lane = 0; lane < lanes; ++lane) {
        const int sample = work.pending[first + lane];
        const double smallest = searching ? searchedRoom(lane) : rakedRoom(lane, sample);
        if (smallest > 0.0) continue;
        blocked = !deferring;
        if (smallest < closestGap) {
          closestGap = smallest;
          closest = sample;
          closestLane = lane;
        }
      }
      if (closest >= 0 && exactChecks < kMaxExactChecks) {
        ++exactChecks;
        if (unclearedPairsCollide(closest, closestLane)) return SphereMotion::Collides;
      }
    }
    return SphereMotion::Free;
  }

  // Stores every pair's room at `sample` (lane `lane` of the gaps just computed) and settles the pairs without any:
  // floored where a grid keeps them, else deferred (when deferring). Returns the smallest room of the pairs that
  // stop the rake or, for bodies, go to FCL (positive when there is none).
  double rakedRoom(int lane, int sample) {
    double* room = &work.rooms[static_cast<std::size_t>(sample) * pairs];
    const float* gaps = work.gaps.data() + lane;
    for (int p = 0; p < bodies; ++p) room[p] = static_cast<double>(gaps[p * kLanes]) - keptObstacle;
    for (int p = bodies; p < pairs; ++p) room[p] = static_cast<double>(gaps[p * kLanes]) - keptSelf;
    double smallest = kInfinity;
    for (int p = 0; p < pairs; ++p) {
      if (room[p] > 0.0 || skipped(p)) continue;
      if (gridKeeps(p)) {
        settle(p, work.floored);
        continue;
      }
      if (!deferring) {
        smallest = std::min(smallest, room[p]);
        continue;
      }
      settle(p, work.deferred);
      if (p < bodies) smallest = std::min(smallest, room[p]);  // a self pair's spheres are close everywhere
    }
    return smallest;
  }

  // The search's smallest room at lane `lane` over the pairs it measures.
  double searchedRoom(int lane) const {
    double smallest = kInfinity;
    for (int p = 0; p < pairs; ++p)
      if (!skipped(p)) smallest = std::min(smallest, static_cast<double>(work.gaps[p * kLanes + lane]) - kept(p));
    return smallest;
  }

  // Marks pair p floored or deferred; covered() no longer asks it anything (its rate there -infinity).
  void settle(int p, std::vector<char>& mark) {
    mark[p] = 1;
    work.coveredRates[p] = -kInfinity;
  }

  double kept(int p) const { return p < bodies ? keptObstacle : keptSelf; }
  // Whether self pair p's floor grid proves it apart by more than keptSelf all along the motion. Asked only where
  // the spheres cannot separate the pair: a grid measures its cells when first asked.
  bool gridKeeps(int p) const {
    if (p < bodies) return false;
    const Implementation& impl = implementationOf(model);
    const auto& group = impl.selfGroups[prefilter.selfGroupOf(p - bodies)];
    return group.floorGrid && group.floorGrid->keepsAlong(qa, qb, keptSelf, groupAxes(impl, data, group));
  }
  // A pair the spheres no longer measure on this motion: its floor keeps it apart, or it is deferred. The search
  // measures only the deferred bodies (their collisions are what it looks for).
  bool skipped(int p) const {
    if (searching) return p >= bodies || !work.deferred[p];
    return work.floored[p] || work.deferred[p];
  }

  // FCL's answer at sample `sample` (lane `lane` of the batch just evaluated) whether the state collides, from the
  // pairs whose spheres touch there (detail::unclearedPairsCollide), less the floored ones and, in the search, all but
  // the deferred bodies.
  bool unclearedPairsCollide(int sample, int lane) {
    data.motionJoints = qa + work.samples[sample] * (qb - qa);
    work.skip.resize(pairs);
    for (int p = 0; p < pairs; ++p) work.skip[p] = work.floored[p] || (searching && skipped(p));
    return detail::unclearedPairsCollide(model, data, data.motionJoints, lane, work.skip.data());
  }

  // Whether every pair's rooms at samples i and j cover the interval between them (a settled pair's rate is
  // -infinity: any room does), without a branch per pair.
  bool covered(int i, int j) const {
    const double length = work.samples[j] - work.samples[i];
    const double* roomI = &work.rooms[static_cast<std::size_t>(i) * pairs];
    const double* roomJ = &work.rooms[static_cast<std::size_t>(j) * pairs];
    bool all = true;
    for (int p = 0; p < pairs; ++p) all &= roomI[p] + roomJ[p] >= work.coveredRates[p] * length;
    return all;
  }

  // Looks for a collision only: evenly spaced states (kSearchStep), coarsest stride first; of the deferred bodies'
  // obstacle pairs when deferring, else of every pair.
  SphereMotion search() {
    searching = deferring;
    const int count = std::min(kMaxSamples, static_cast<int>(std::ceil((qb - qa).cwiseAbs().maxCoeff() / kSearchStep)));
    work.pending.clear();
    for (int stride = kMaxSamples; stride >= 1; stride /= 2) {  // each k once: its lowest set bit is `stride`
      for (int k = stride; k < count; k += 2 * stride) addSample(static_cast<double>(k) / count);
    }
    return evaluate(1.0 / count) == SphereMotion::Collides ? SphereMotion::Collides : SphereMotion::Unknown;
  }

  int addSample(double s) {
    work.samples.push_back(s);
    // Grown, never cleared: rakedRoom writes every pair's room of a sample before covered() reads it, so zeroing
    // the rooms of every motion's samples anew (up to 256 × pairs doubles) was 2.5 % of a long motion's check.
    const std::size_t needed = work.samples.size() * static_cast<std::size_t>(pairs);
    if (work.rooms.size() < needed) work.rooms.resize(needed);
    work.pending.push_back(static_cast<int>(work.samples.size()) - 1);
    return static_cast<int>(work.samples.size()) - 1;
  }
};

}  // namespace

SphereMotion sphereMotion(const CollisionModel& model, Workspace& data, const robot::JointRef& qa,
                          const robot::JointRef& qb, double minimumClearance, bool deferPairs) {
  const Implementation& impl = implementationOf(model);
  if (!impl.prefilter || !impl.prefilter->usable()) return SphereMotion::Unknown;
  const SpherePrefilter& prefilter = *impl.prefilter;
  SphereWorkspace& work = *data.spheres;
  const int bodies = prefilter.tables().bodyCount, pairs = prefilter.pairCount();
  const Eigen::VectorXd step = (qb - qa).cwiseAbs();
  work.rates.resize(pairs);
  work.floored.assign(pairs, 0);
  work.deferred.assign(pairs, 0);
  const double keptSelf = keptClearance(requiredDistance(true, minimumClearance));
  for (int b = 0; b < bodies; ++b) work.rates[b] = impl.jointReach.row(b).dot(step);
  for (int p = bodies; p < pairs; ++p) {
    const auto& group = impl.selfGroups[prefilter.selfGroupOf(p - bodies)];
    work.rates[p] = group.relativeReach.dot(step);
    work.floored[p] = group.floor >= keptSelf;
  }
  work.coveredRates = work.rates;
  for (int p = bodies; p < pairs; ++p)
    if (work.floored[p]) work.coveredRates[p] = -kInfinity;
  // The rigid pairs left out of the tables keep their one distance all along the motion.
  for (const auto& group : impl.selfGroups) {
    if (group.rigid && group.rigidDistance < keptSelf) return SphereMotion::Unknown;
  }

  Rake rake{model, prefilter, data, work, qa, qb, keptClearance(minimumClearance), keptSelf, bodies, pairs, deferPairs};
  work.samples.clear();
  work.pending.clear();
  work.intervals.clear();
  for (int k = 0; k < kLanes; ++k) rake.addSample(static_cast<double>(k) / (kLanes - 1));
  for (int k = 0; k + 1 < kLanes; ++k) work.intervals.emplace_back(k, k + 1);
  double h = 1.0 / (kLanes - 1);
  while (true) {
    if (rake.evaluate(h) == SphereMotion::Collides) return SphereMotion::Collides;
    if (rake.blocked) return rake.search();
    work.pending.clear();
    work.next.clear();
    for (const auto& interval : work.intervals)
      if (!rake.covered(interval.first, interval.second)) work.next.push_back(interval);
    if (work.next.empty()) {
      const auto firstSelfPair = work.deferred.begin() + bodies;
      if (std::find(work.deferred.begin(), firstSelfPair, 1) != firstSelfPair)  // a body deferred
        return rake.search() == SphereMotion::Collides ? SphereMotion::Collides : SphereMotion::PairsLeft;
      return std::find(firstSelfPair, work.deferred.end(), 1) == work.deferred.end() ? SphereMotion::Free
                                                                                     : SphereMotion::PairsLeft;
    }
    // Spread a batch's worth of new samples over the uncovered intervals (at least one each).
    const int each = std::max(1, kLanes / static_cast<int>(work.next.size()));
    if (static_cast<int>(work.samples.size() + work.next.size() * each) > kMaxSamples) return SphereMotion::Unknown;
    work.intervals.clear();
    h = 0.0;
    for (const auto& [i, j] : work.next) {
      const double from = work.samples[i], length = (work.samples[j] - from) / (each + 1);
      h = std::max(h, length);
      int previous = i;
      for (int k = 1; k <= each; ++k) {
        const int sample = rake.addSample(from + k * length);
        work.intervals.emplace_back(previous, sample);
        previous = sample;
      }
      work.intervals.emplace_back(previous, j);
    }
  }
}

}  // namespace arcplan::collision::detail
