// PathCertifier (motion_check.h): a joint path certified motion by motion while it grows, each pair spending the
// clearance it had at its last measurement (its anchor) on the motion bounds of the waypoints since.
#include <cmath>
#include <vector>

#include "arcplan/collision/motion_check.h"
#include "certified_motion.h"
#include "model_implementation.h"
#include "motion_clearance.h"

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
    : model_(model), data_(data), minimumClearance_(minimumClearance) {
  validate(MotionCheckOptions{MotionCheck::Certified, 0.01, minimumClearance});
  // A path of its own (motionAxis): directions found while certifying it are taken for its later waypoints, none
  // from earlier queries.
  ++detail::workspaceOf(data_).motion;
  budget_.resize(detail::implementationOf(model).groups.size());
  used_.resize(budget_.size());
  bound_.resize(budget_.size());
}

bool PathCertifier::anchorAll(const robot::JointRef& q) {
  const Implementation& impl = detail::implementationOf(model_);
  detail::updateRobot(model_, detail::workspaceOf(data_), q);
  ++measurements_;
  for (std::size_t k = 0; k < budget_.size(); ++k) {
    const double m = impl.groups[k]->required(minimumClearance_);  // this pair's own m
    // The capsule bounds are taken as soon as they leave a few centimetres to spend: enough for several waypoints.
    const detail::PairMeasurement measured =
        detail::measurePair(model_, detail::workspaceOf(data_), k, kAnchorBudget + m, m);
    if (measured.tooClose) return false;
    budget_[k] = measured.gap - m;  // what the pair may close in before it is m apart
    used_[k] = 0.0;
  }
  last_ = q;
  return true;
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
  step_ = (q - last_).cwiseAbs();
  std::vector<std::size_t> open;  // pairs whose budget does not cover the motion
  for (std::size_t k = 0; k < budget_.size(); ++k) {
    bound_[k] = impl.groups[k]->relativeReach.dot(step_);
    if (used_[k] + bound_[k] >= budget_[k]) open.push_back(k);
  }
  const auto accept = [&] {
    for (std::size_t k = 0; k < budget_.size(); ++k) used_[k] += bound_[k];
    last_ = q;
    return true;
  };
  if (open.empty()) return accept();
  const auto mOf = [&](std::size_t k) { return impl.groups[k]->required(minimumClearance_); };
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
