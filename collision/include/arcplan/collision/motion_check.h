#pragma once
// Collision checks of a straight joint-space motion q(s) = qa + s·(qb − qa), s ∈ [0, 1].
//
// MotionCheck::Certified proves a motion free ("conservative advancement", after Schwarzer, Saha &
// Latombe's exact collision checking of robot paths): on the motion every point of a link L moves
// at most M_L = Σ_j |Δq_j|·D_jL, where D_jL bounds the distance of L's geometry from joint j's axis
// in every configuration (precomputed by CollisionModel). Each pair keeps its own m: m = minimumClearance
// between the robot and an obstacle, m = min(minimumClearance, kSelfClearance) between two of the robot's
// own bodies (requiredDistance, collision_model.h). A pair of bodies at distance ≥ g at q(s) therefore
// stays at least its m apart on (s − (g − m)/M, s + (g − m)/M), M the rate at which the pair can approach
// (the link's M_L against an obstacle; for two links only the joints that move them relative to each other
// count). The check measures every non-allowed pair at the two ends and then moves a front from each end,
// each pair re-measured where its certificate runs out, until the certificates meet. Cheap lower bounds
// (the capsules of the broad phase) are used where they certify the rest of the motion or are at least
// m + margin (margin = acceptanceMargin(m) = min(m/4, 0.5 mm), with the pair's m), exact distances (FCL)
// below. A pair measured closer than its m + margin rejects the motion. So, per pair with the pair's m:
//   - an accepted motion keeps every pair at least its m apart at every point (so one that collides is
//     rejected);
//   - a motion along which every pair keeps at least its m + margin is always accepted;
//   - a motion that comes closer than that may go either way.
// The number of measurements is bounded: each advances a pair's certificate by at least margin / M.
//
// MotionCheck::Discrete is the classic sampled check (states no joint step more than maxJointStep
// apart); it can miss an obstacle thinner than what a link sweeps in one step (a 0.01 rad step of the
// UR10e's base joint moves the wrist up to 1.8 cm), so it is kept for comparisons.
#include <algorithm>
#include <limits>

#include <Eigen/Core>

#include "arcplan/collision/collision_model.h"
#include "arcplan/robot/kinematics.h"

namespace arcplan::collision {

enum class MotionCheck { Discrete, Certified };
const char* toString(MotionCheck method);

struct MotionCheckOptions {
  MotionCheck method = MotionCheck::Certified;
  double maxJointStep = 0.01;  // Discrete: largest joint change between checked states [rad]
  // Certified: what an accepted motion keeps everywhere [m], >= 1e-5, between the robot and obstacles; self
  // pairs keep min(minimumClearance, kSelfClearance) (requiredDistance, collision_model.h). The default is
  // kSelfClearance: with it every pair keeps the same.
  double minimumClearance = kSelfClearance;
};

// Throws arcplan::Error naming the field when maxJointStep or minimumClearance is out of range.
void validate(const MotionCheckOptions& options);

// The margin above minimumClearance m below which a certified check rejects a pair it measures: a quarter of
// m, at most 0.5 mm, which a motion that keeps m + 2 mm between samples 1 mm apart still passes; every step
// advances by at least margin/rate. Callers that place or explain a certificate's stop (approach zones, the
// arc planner's screen) ask the same rule here.
inline double acceptanceMargin(double minimumClearance) { return std::min(0.25 * minimumClearance, 5e-4); }

// Whether every pair at q keeps at least its own m + acceptanceMargin(m) (m per pair as above, of
// minimumClearance > 0): false where a certified motion at minimumClearance may stop, as it rejects a pair it
// measures closer. Answered with hasClearance's bounds.
bool keepsAcceptanceMargin(const CollisionModel& model, CollisionData& data, const robot::JointRef& q,
                           double minimumClearance);

// The pair at q that keeps least of what a certified motion at minimumClearance accepts (its own m +
// acceptanceMargin(m), as keepsAcceptanceMargin): its names, exact distance and that distance less what is accepted
// (below 0 a certified motion may stop at q); an obstacle pair before a self pair that falls as short. The distance is
// the one distance() reports for that pair's kind, but pairs whose bounds show they keep more are never measured (what
// explains a refused waypoint). Throws arcplan::Error as keepsAcceptanceMargin.
struct Shortfall {
  NamePair pair;  // (link, obstacle) or (link, link)
  bool self = false;
  double distance = std::numeric_limits<double>::infinity();
  double shortfall = std::numeric_limits<double>::infinity();
};
Shortfall smallestShortfall(const CollisionModel& model, CollisionData& data, const robot::JointRef& q,
                            double minimumClearance);

// Whether the straight motion qa -> qb is collision-free. Certified covers the closed motion [0, 1]
// (qa too); Discrete checks the states at fractions k/n, k = 1..n (qa is taken as valid, as OMPL
// does). When lastValidFraction is given, the motion is checked from qa on, and on failure it gets
// the fraction of the last state known to be valid (in [0, 1); for Certified a state the check
// measured clear, with the whole motion up to it certified; 0 if qa itself fails).
bool isMotionCollisionFree(const CollisionModel& model, CollisionData& data, const robot::JointRef& qa,
                           const robot::JointRef& qb, double* lastValidFraction = nullptr,
                           const MotionCheckOptions& options = {});

// Certifies a joint path motion by motion while it grows: for planners that build a path waypoint by
// waypoint (the arc planner) and want every motion validated. A pair's clearance measured at one
// waypoint also certifies the following motions as long as the pair's accumulated motion bound
// stays below it, so a densely sampled path (waypoints 1 cm apart) needs a measurement only every
// few waypoints instead of two per motion. What it accepts carries the guarantee of the certified
// check above: every configuration on an accepted motion keeps each pair at least its own m apart
// (minimumClearance from obstacles, requiredDistance(true, minimumClearance) between the robot's own bodies).
class PathCertifier {
public:
  // model and data must outlive the certifier; data is used as its workspace.
  PathCertifier(const CollisionModel& model, CollisionData& data, double minimumClearance = kSelfClearance);

  // Starts a path at q: false if q collides or a pair is closer than its own m (budgets per pair: gap − m).
  bool start(const robot::JointRef& q);
  // Certifies the straight motion from the last accepted configuration to q and accepts q; false
  // (and q not accepted) if the motion cannot be certified.
  bool extend(const robot::JointRef& q);
  // The configurations the following extend() calls will take, in order, one per column (a converted path's
  // waypoints): with the model's sphere prefilter their sphere gaps are computed 8 per kernel call as the walk
  // reaches them, and a pair whose gaps cover a motion needs no measurement. A hint: an extend() to any other
  // configuration measures as without it, and what is accepted is the same guarantee either way. start() at the
  // first of them takes its pairs' budgets from the spheres too.
  void expect(const Eigen::Ref<const Eigen::MatrixXd>& waypoints);
  // Configurations where pairs were measured so far (forward kinematics and distances): the cost of the
  // certification. The link poses a motion's own bounds take (below) are not counted.
  int measurements() const { return measurements_; }

private:
  bool anchorAll(const robot::JointRef& q);
  // At an expected waypoint where the joint steps' bound (relativeReach · |Δq|) leaves pairs open: each pair's bound of
  // the motion to q lowered to its links' chord rates (detail::chordRate), from the link poses at last_ and q.
  void tightenBounds(const robot::JointRef& q);
  // q's column of expect()'s waypoints when it is the next one (or the one after), else -1.
  Eigen::Index expectedColumn(const robot::JointRef& q);
  // The sphere gaps (pairs × 8, SpherePrefilter::gaps' layout) holding expect()'s column `waypoint` and its lane
  // there: computed with the 7 waypoints after it when not held yet.
  const float* expectedGaps(Eigen::Index waypoint, int& lane);

  const CollisionModel& model_;
  CollisionData& data_;
  double minimumClearance_;
  robot::JointVector last_, step_;
  // Per pair: clearance at its anchor waypoint, motion bound consumed since, bound of this motion.
  std::vector<double> budget_, used_, bound_;
  int measurements_ = 0;
  // expect(): the waypoints, the next one's column, the columns whose sphere gaps windowGaps_ holds, and per group
  // its pair of those gaps (-1: none, or no prefilter).
  Eigen::MatrixXd expected_;
  Eigen::Index nextExpected_ = 0, windowBegin_ = 0, windowEnd_ = 0;
  std::vector<float> windowGaps_;
  std::vector<int> gapPairs_;
  std::vector<std::pair<std::size_t, double>> sphereBudgets_;  // per pair the spheres covered: its budget at q
  // Link poses at last_ (when lastPosed_) and at the configuration being certified (when nextPosed_), and per
  // body with geometry its chord rate on the motion between them.
  robot::KinematicsData lastPoses_, nextPoses_;
  bool lastPosed_ = false, nextPosed_ = false;
  std::vector<double> chordRates_;
};

// Segments of a discrete check: ceil(largest |qb_j − qa_j| / maxJointStep), at least 1.
int discreteSegmentCount(const robot::JointRef& qa, const robot::JointRef& qb, double maxJointStep);

}  // namespace arcplan::collision
