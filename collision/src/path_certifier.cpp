// PathCertifier (motion_check.h): a joint path certified motion by motion while it grows, each pair spending the
// clearance it had at its last measurement (its anchor) on the motion bounds of the waypoints since.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "arcplan/collision/motion_check.h"
#include "arcplan/common/error.h"
#include "certified_motion.h"
#include "model_implementation.h"
#include "motion_bounds.h"
#include "motion_clearance.h"
#include "sphere_prefilter.h"

namespace arcplan::collision {
namespace {

using detail::checkJoints;
using detail::Implementation;

// What PathCertifier asks of a pair at a new anchor beyond minimumClearance [m].
constexpr double kAnchorBudget = 0.05;
// Measurements between a motion's ends before the whole-motion check decides (advanceBetweenEnds).
constexpr int kBetweenEnds = 10;

// Per uncovered pair, the fraction of the motion certified from its start, (g_a − m)/B, and from its end, 1 −
// (g_b − m)/B; the front of the pairs not yet covered is measured (one forward kinematics for all of them), each
// pair measured there extending its certificate by (g − m)/B, until the certificates meet for every pair. At most
// kBetweenEnds measurements, each of which must keep the acceptance margin: else the caller's certified check
// decides (it rates each part pair on its own, which may need fewer steps).
struct BetweenEnds {
  const CollisionModel& model;
  detail::Workspace& data;
  double minimumClearance;
  const robot::JointVector& qa;
  const robot::JointRef& qb;
  const std::vector<std::size_t>& pairs;  // the uncovered pairs (their groups)
  const std::vector<double>& rate;        // per group, its motion bound B over qa -> qb
  std::vector<double> from, to;           // per uncovered pair, its certificates from each end (fractions)
};

bool advanceBetweenEnds(BetweenEnds& motion, int& measurements) {
  const Implementation& impl = detail::implementationOf(motion.model);
  const auto& uncovered = motion.pairs;
  auto &from = motion.from, &to = motion.to;
  for (int measured = 0;; ++measured) {
    double s = 2.0;
    for (std::size_t u = 0; u < uncovered.size(); ++u)
      if (from[u] <= to[u]) s = std::min(s, from[u]);
    if (s > 1.0) return true;
    if (measured == kBetweenEnds) return false;
    motion.data.motionJoints = motion.qa + s * (motion.qb - motion.qa);
    detail::updateRobot(motion.model, motion.data, motion.data.motionJoints);
    ++measurements;
    for (std::size_t u = 0; u < uncovered.size(); ++u) {
      if (from[u] > to[u] || from[u] > s) continue;
      const std::size_t k = uncovered[u];
      const double m = impl.groups[k]->required(motion.minimumClearance);
      const double wanted = m + (to[u] - s) * motion.rate[k];  // what certifies the rest
      const detail::PairMeasurement gap = detail::measurePair(motion.model, motion.data, k, wanted, m);
      if (gap.tooClose || gap.gap - m < acceptanceMargin(m)) return false;
      from[u] = s + (gap.gap - m) / motion.rate[k];
    }
  }
}

}  // namespace

PathCertifier::PathCertifier(const CollisionModel& model, CollisionData& data, double minimumClearance)
    : model_(model),
      data_(data),
      minimumClearance_(minimumClearance),
      lastPoses_(model.robot()),
      nextPoses_(model.robot()) {
  validate(MotionCheckOptions{MotionCheck::Certified, 0.01, minimumClearance});
  // A path of its own (motionAxis): directions found while certifying it are taken for its later waypoints, none
  // from earlier queries.
  ++detail::workspaceOf(data_).motion;
  const Implementation& impl = detail::implementationOf(model);
  chordRates_.resize(impl.linkCapsules.size());
  budget_.resize(impl.groups.size());
  used_.resize(budget_.size());
  bound_.resize(budget_.size());
  if (impl.prefilter && impl.prefilter->usable()) {
    for (std::size_t k = 0; k < impl.groups.size(); ++k) gapPairs_.push_back(impl.prefilter->gapPairOfGroup(impl, k));
  }
}

void PathCertifier::expect(const Eigen::Ref<const Eigen::MatrixXd>& waypoints) {
  if (waypoints.rows() != model_.robot().dof()) {
    throw Error("path certifier: expected waypoints need " + std::to_string(model_.robot().dof()) +
                " joint values each, got " + std::to_string(waypoints.rows()));
  }
  expected_ = waypoints;
  nextExpected_ = windowBegin_ = windowEnd_ = 0;
}

const float* PathCertifier::expectedGaps(Eigen::Index waypoint, int& lane) {
  using detail::prefilter::kLanes;
  if (waypoint < windowBegin_ || waypoint >= windowEnd_) {
    const Implementation& impl = detail::implementationOf(model_);
    const detail::SpherePrefilter& prefilter = *impl.prefilter;
    detail::SphereWorkspace& work = *detail::workspaceOf(data_).spheres;
    windowBegin_ = waypoint;
    windowEnd_ = std::min<Eigen::Index>(waypoint + kLanes, expected_.cols());
    prefilter.loadLanes(work, expected_.col(waypoint).data(), expected_.rows(),
                        static_cast<int>(windowEnd_ - windowBegin_));
    // Refined until a pair has the budget a new anchor asks of it (or is as close as its spheres tell).
    const int bodies = prefilter.tables().bodyCount, pairs = prefilter.pairCount();
    const auto enough = [&](bool self) {
      return static_cast<float>(requiredDistance(self, minimumClearance_) + kAnchorBudget + prefilter.margin());
    };
    std::fill(work.enough.begin(), work.enough.begin() + bodies, enough(false));
    std::fill(work.enough.begin() + bodies, work.enough.begin() + pairs, enough(true));
    prefilter.gaps(work);
    // Copied: other queries between two extend() calls use the workspace's gaps.
    windowGaps_.assign(work.gaps.begin(), work.gaps.begin() + static_cast<std::ptrdiff_t>(pairs) * kLanes);
  }
  lane = static_cast<int>(waypoint - windowBegin_);
  return windowGaps_.data();
}

Eigen::Index PathCertifier::expectedColumn(const robot::JointRef& q) {
  // The next waypoint, or the one after it when a motion piece ended between the two (an approach zone's boundary).
  for (Eigen::Index k = nextExpected_; k < std::min<Eigen::Index>(nextExpected_ + 2, expected_.cols()); ++k) {
    if (expected_.col(k) == q) {
      nextExpected_ = k + 1;
      return k;
    }
  }
  return -1;
}

bool PathCertifier::anchorAll(const robot::JointRef& q) {
  const Implementation& impl = detail::implementationOf(model_);
  // At an expected waypoint the spheres give most pairs their budget; the others are measured.
  const Eigen::Index expectedAt = gapPairs_.empty() ? -1 : expectedColumn(q);
  int lane = 0;
  const float* gaps = expectedAt >= 0 ? expectedGaps(expectedAt, lane) : nullptr;
  bool placed = false;
  for (std::size_t k = 0; k < budget_.size(); ++k) {
    const double m = impl.groups[k]->required(minimumClearance_);  // this pair's own m
    used_[k] = 0.0;
    if (gaps != nullptr && gapPairs_[k] >= 0) {
      const double room =
          static_cast<double>(gaps[static_cast<std::size_t>(gapPairs_[k]) * detail::prefilter::kLanes + lane]) - m;
      if (room >= kAnchorBudget) {
        budget_[k] = room;
        continue;
      }
    }
    if (!placed) {
      detail::updateRobot(model_, detail::workspaceOf(data_), q);
      ++measurements_;
      placed = true;
    }
    // The capsule bounds are taken as soon as they leave a few centimetres to spend: enough for several waypoints.
    const detail::PairMeasurement measured =
        detail::measurePair(model_, detail::workspaceOf(data_), k, kAnchorBudget + m, m);
    if (measured.tooClose) return false;
    budget_[k] = measured.gap - m;  // what the pair may close in before it is m apart
  }
  last_ = q;
  lastPosed_ = false;
  return true;
}

void PathCertifier::tightenBounds(const robot::JointRef& q) {
  const Implementation& impl = detail::implementationOf(model_);
  if (!lastPosed_) robot::forwardKinematics(model_.robot(), last_, lastPoses_);
  lastPosed_ = true;
  robot::forwardKinematics(model_.robot(), q, nextPoses_);
  nextPosed_ = true;
  for (std::size_t b = 0; b < chordRates_.size(); ++b) {
    const int link = impl.linkCapsuleLink[b];
    chordRates_[b] =
        detail::chordRate(impl, static_cast<int>(b), lastPoses_.linkPoses[link], nextPoses_.linkPoses[link], step_);
  }
  // Every pair's: those covered already spend less of their budgets too.
  for (std::size_t k = 0; k < bound_.size(); ++k) {
    const auto& group = *impl.groups[k];
    const double chord = chordRates_[group.firstBody] + (group.self ? chordRates_[group.secondBody] : 0.0);
    bound_[k] = std::min(bound_[k], chord);
  }
}

bool PathCertifier::start(const robot::JointRef& q) {
  checkJoints(model_, q, q);
  return anchorAll(q);
}

// A pair whose budget does not cover the motion is measured again at the motion's start (unless it was measured
// there); if that does not cover it either, at the motion's end: a pair at least g_a apart at the start and g_b at
// the end, approaching at most at rate B over the motion, keeps m everywhere on it when (g_a − m) + (g_b − m) ≥ B
// (the two certificates, (g_a − m)/B from the start and (g_b − m)/B from the end, cover [0, 1]); where they do not
// meet, advanceBetweenEnds measures the pair between them. Near a body a 1 cm waypoint step mostly needs only that
// (on line-box-007, wall-002 and near-end-002 a pair's budget ran out at 98 % of the waypoints and the whole-motion
// check below was left with 1300 of the 13900 motions a fresh budget did not cover), where the whole-motion check and
// new anchors for every pair took several forward kinematics and every pair's bounds. Ends and measurements between
// them settle a pair only where they keep the certified check's acceptance margin (motion_check.h), so what that check
// would refuse at a measured state is still refused; the rest goes to it.
bool PathCertifier::extend(const robot::JointRef& q) {
  checkJoints(model_, last_, q);
  const Implementation& impl = detail::implementationOf(model_);
  detail::Workspace& data = detail::workspaceOf(data_);
  // q's column of expect()'s waypoints, -1 when it is not the next one.
  const Eigen::Index expectedAt = gapPairs_.empty() ? -1 : expectedColumn(q);
  step_ = (q - last_).cwiseAbs();
  nextPosed_ = false;
  std::vector<std::size_t> open;  // pairs whose budget does not cover the motion
  for (std::size_t k = 0; k < budget_.size(); ++k) {
    bound_[k] = impl.groups[k]->relativeReach.dot(step_);
    if (used_[k] + bound_[k] >= budget_[k]) open.push_back(k);
  }
  sphereBudgets_.clear();
  const auto accept = [&] {
    for (std::size_t k = 0; k < budget_.size(); ++k) used_[k] += bound_[k];
    for (const auto& [k, budget] : sphereBudgets_) {
      budget_[k] = budget;
      used_[k] = 0.0;
    }
    last_ = q;
    // q's link poses, when this motion's bounds took them, are the next motion's start.
    if (nextPosed_) std::swap(lastPoses_, nextPoses_);
    lastPosed_ = nextPosed_;
    return true;
  };
  if (open.empty()) return accept();
  const auto mOf = [&](std::size_t k) { return impl.groups[k]->required(minimumClearance_); };
  // An expected waypoint's sphere gaps, lower bounds of its pairs' distances: a pair whose room there (gap − m) and
  // the room left of its budget at the motion's start together reach the motion's bound is certified by the two
  // certificates, one from each end, and anchored at q with the larger of what it has left.
  int lane = 0;
  const float* gaps = expectedAt >= 0 ? expectedGaps(expectedAt, lane) : nullptr;
  const auto coveredBySpheres = [&](std::size_t k) {
    if (gapPairs_[k] < 0) return false;
    const double room =
        static_cast<double>(gaps[static_cast<std::size_t>(gapPairs_[k]) * detail::prefilter::kLanes + lane]) - mOf(k);
    const double left = std::max(0.0, budget_[k] - used_[k]);
    if (room < 0.0 || left + room < bound_[k]) return false;
    sphereBudgets_.emplace_back(k, std::max(room, left - bound_[k]));
    return true;
  };
  if (gaps != nullptr) {
    open.erase(std::remove_if(open.begin(), open.end(), coveredBySpheres), open.end());
    if (open.empty()) return accept();
  }
  // Before anything is measured, the bounds of the links' own moves: on a dense path the joint steps' bound is several
  // times what the links move, and with them the spheres settle a pair again. Only where the spheres are at hand:
  // without them the measurement at the motion's start below settles almost every such pair anyway (the thesis shape's
  // walk: 6 % of its motions settled by the chords, two forward kinematics a motion more, 105 -> 131 us a solve).
  if (gaps != nullptr) {
    tightenBounds(q);
    open.erase(std::remove_if(open.begin(), open.end(),
                              [&](std::size_t k) { return used_[k] + bound_[k] < budget_[k] || coveredBySpheres(k); }),
               open.end());
    if (open.empty()) return accept();
  }
  // At the motion's start, the pairs not measured there (a pair anchored there was measured for a new anchor,
  // which asks more of its bounds than this motion would).
  bool startMeasured = false;
  for (std::size_t k : open) {
    if (used_[k] == 0.0) continue;
    if (!startMeasured) {
      detail::updateRobot(model_, data, last_);
      ++measurements_;
      startMeasured = true;
    }
    const double m = mOf(k);
    const detail::PairMeasurement measured = detail::measurePair(model_, data, k, bound_[k] + m, m);
    if (measured.tooClose) return false;
    budget_[k] = measured.gap - m;
    used_[k] = 0.0;
  }
  std::vector<std::size_t> uncovered;
  for (std::size_t k : open)
    if (bound_[k] >= budget_[k]) uncovered.push_back(k);
  if (uncovered.empty()) return accept();
  // At the motion's end: each uncovered pair measured as for a new anchor there.
  detail::updateRobot(model_, data, q);
  ++measurements_;
  std::vector<double> endBudget(uncovered.size());
  bool kept = true;  // every measurement of the uncovered pairs kept the acceptance margin
  for (std::size_t u = 0; u < uncovered.size(); ++u) {
    const std::size_t k = uncovered[u];
    const double m = mOf(k), margin = acceptanceMargin(m);
    const detail::PairMeasurement measured = detail::measurePair(model_, data, k, kAnchorBudget + m, m);
    if (measured.tooClose) return false;
    endBudget[u] = measured.gap - m;
    kept = kept && budget_[k] >= margin && endBudget[u] >= margin;
  }
  BetweenEnds motion{model_, data, minimumClearance_, last_, q, uncovered, bound_, {}, {}};
  if (kept) {
    for (std::size_t u = 0; u < uncovered.size(); ++u) {
      const double rate = bound_[uncovered[u]];  // > 0: the pair's budget (at least the margin) does not cover it
      motion.from.push_back(budget_[uncovered[u]] / rate);
      motion.to.push_back(1.0 - endBudget[u] / rate);
    }
  }
  if (!(kept && advanceBetweenEnds(motion, measurements_))) {
    // Not from the ends: the certified check of the whole motion (every pair, each part pair at its own rate).
    ++measurements_;
    if (!detail::certifiedMotionFree(model_, data_, last_, q, nullptr, minimumClearance_)) return false;
  }
  // The uncovered pairs anchored at the motion's end; every other pair keeps its budget.
  accept();
  for (std::size_t u = 0; u < uncovered.size(); ++u) {
    budget_[uncovered[u]] = endBudget[u];
    used_[uncovered[u]] = 0.0;
  }
  return true;
}

}  // namespace arcplan::collision
