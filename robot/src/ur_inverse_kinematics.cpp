#include "arcplan/robot/ur_inverse_kinematics.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arcplan/common/error.h"
#include "ur_chain.h"

namespace arcplan::robot {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// Below this, sin(q5) is treated as zero (wrist singularity) and |cos q3| as one (elbow stretched).
constexpr double kSingularityTolerance = 1e-10;

double wrapToPi(double angle) {
  // Rounding to the nearest multiple of 2·pi instead of std::remainder: the exact libm remainder
  // is several times slower and was a fifth of an arc-planner solve.
  angle -= kTwoPi * std::nearbyint(angle / kTwoPi);  // in [-pi, pi]
  return angle <= -M_PI ? angle + kTwoPi : angle;
}

Eigen::Isometry3d dhLink(double theta, double d, double a, double alpha) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  const double ct = std::cos(theta), st = std::sin(theta), ca = std::cos(alpha), sa = std::sin(alpha);
  t.linear() << ct, -st * ca, st * sa, st, ct * ca, -ct * sa, 0.0, sa, ca;
  t.translation() << a * ct, a * st, d;
  return t;
}

}  // namespace

Eigen::Isometry3d urDhForwardKinematics(const UrDhParameters& dh, const Vector6& q) {
  return dhLink(q[0], dh.d1, 0.0, M_PI_2) * dhLink(q[1], 0.0, dh.a2, 0.0) * dhLink(q[2], 0.0, dh.a3, 0.0) *
         dhLink(q[3], dh.d4, 0.0, M_PI_2) * dhLink(q[4], dh.d5, 0.0, -M_PI_2) * dhLink(q[5], dh.d6, 0.0, 0.0);
}

UrInverseKinematics::UrInverseKinematics(const RobotModel& model) {
  for (int j = 0; j < model.dof() && j < 6; ++j) {
    lower_[j] = model.joints()[j].limits.lower;
    upper_[j] = model.joints()[j].limits.upper;
  }
  auto chain = std::make_shared<const detail::JointChain>(detail::jointChainOf(model));
  const detail::UrChainFit fit = detail::fitUrChain(*chain, model.name());
  const double tolerance = model.calibrated() ? kCalibratedChainTolerance : kUrdfChainTolerance;
  if (fit.translationDeviation > tolerance || fit.rotationDeviation > tolerance) {
    std::ostringstream message;
    message << "'" << model.name() << "' is not a UR-type arm: its chain differs from the UR chain fitted to it by "
            << fit.translationDeviation << " m and " << fit.rotationDeviation
            << " rad at a test configuration (tolerance " << tolerance << " m and rad"
            << (model.calibrated() ? ", for a calibrated arm)"
                                   : "; a calibrated UR arm loads with robot {ur_type, kinematics: FILE})");
    throw Error(message.str());
  }
  dh_ = fit.dh;
  dh0ToBase_ = fit.baseToDh0.inverse();
  tipToDh6_ = fit.dh6ToTip.inverse();
  translationDeviation_ = fit.translationDeviation;
  rotationDeviation_ = fit.rotationDeviation;
  // Below this the ideal chain's solutions already reproduce poses to rounding noise.
  constexpr double kExactChain = 1e-12;
  if (fit.translationDeviation > kExactChain || fit.rotationDeviation > kExactChain) {
    refinedChain_ = std::move(chain);
    // The true arm may reach a little farther than the ideal one: cos q3 of the ideal chain may then
    // exceed 1 by what that deviation changes the wrist distance, d(cos q3) = r dr / (a2 a3).
    reachSlack_ += 2.0 * (std::abs(dh_.a2) + std::abs(dh_.a3)) * fit.translationDeviation / std::abs(dh_.a2 * dh_.a3);
  }
}

double UrInverseKinematics::awayFromMergedBranches(double angle, double inside) {
  return inside > 0.0 ? std::clamp(angle, inside, M_PI - inside) : angle;
}

bool UrInverseKinematics::refine(const Eigen::Isometry3d& tipPose, Vector6& q) const {
  if (!detail::refineOnChain(*refinedChain_, tipPose, q)) return false;
  for (auto& v : q) v = wrapToPi(v);
  return true;
}

// The closed form goes joint group by joint group: the shoulder choice fixes q1, the wrist choice q5
// and q6, the elbow choice q2, q3, q4. Each step is a function so that one branch can be solved
// without the other seven (the planners track one branch along a path).
struct UrInverseKinematics::TargetFrame {
  Eigen::Vector3d n, o, a, p;  // tip pose as DH frame 6 in DH frame 0 (columns and origin)
};

struct UrInverseKinematics::ShoulderStep {
  double q1, s1, c1;
};

struct UrInverseKinematics::WristStep {
  double q5, s5, c5, q6, s6, c6;
};

UrInverseKinematics::TargetFrame UrInverseKinematics::targetFrame(const Eigen::Isometry3d& tipPose) const {
  const Eigen::Isometry3d t06 = dh0ToBase_ * tipPose * tipToDh6_;
  return {t06.linear().col(0), t06.linear().col(1), t06.linear().col(2), t06.translation()};
}

std::optional<UrInverseKinematics::ShoulderStep> UrInverseKinematics::shoulderStep(const TargetFrame& target,
                                                                                   int shoulder, double inside) const {
  // The wrist-2 centre lies at distance d4 from the vertical arm plane.
  const Eigen::Vector3d p5 = target.p - dh_.d6 * target.a;
  const double rho = std::hypot(p5.x(), p5.y());
  if (rho < std::abs(dh_.d4) * (1.0 - 1e-12) - 2.0 * translationDeviation_) return std::nullopt;
  const double phi = awayFromMergedBranches(std::acos(std::clamp(dh_.d4 / rho, -1.0, 1.0)), inside);
  const double q1 = std::atan2(p5.y(), p5.x()) + M_PI_2 + (shoulder == 0 ? phi : -phi);
  return ShoulderStep{q1, std::sin(q1), std::cos(q1)};
}

UrInverseKinematics::WristStep UrInverseKinematics::wristStep(const TargetFrame& target, const ShoulderStep& shoulder,
                                                              int wrist, double q6AtWristSingularity,
                                                              double inside) const {
  const auto& [n, o, a, p] = target;
  const double s1 = shoulder.s1, c1 = shoulder.c1;
  // q5 from the tool point's offset from the arm plane.
  const double c5 = std::clamp((p.x() * s1 - p.y() * c1 - dh_.d4) / dh_.d6, -1.0, 1.0);
  const double q5 = (wrist == 0 ? 1.0 : -1.0) * awayFromMergedBranches(std::acos(c5), inside);
  const double s5 = std::sin(q5);
  double q6 = q6AtWristSingularity;
  if (std::abs(s5) > kSingularityTolerance) {
    q6 = std::atan2(-(o.x() * s1 - o.y() * c1) / s5, (n.x() * s1 - n.y() * c1) / s5);
  }
  return {q5, s5, c5, q6, std::sin(q6), std::cos(q6)};
}

std::optional<Vector6> UrInverseKinematics::elbowStep(const TargetFrame& target, const ShoulderStep& shoulder,
                                                      const WristStep& wrist, int elbow, double inside) const {
  const auto& [n, o, a, p] = target;
  const auto& [d1, a2, a3, d4, d5, d6] = dh_;
  const double s1 = shoulder.s1, c1 = shoulder.c1, s6 = wrist.s6, c6 = wrist.c6;
  // Planar 3R for q2, q3, q4 in the arm plane.
  const Eigen::Vector3d p4 = p - d6 * a + d5 * (s6 * n + c6 * o);
  const double x = p4.x() * c1 + p4.y() * s1;
  const double y = p4.z() - d1;
  const double c3raw = (x * x + y * y - a2 * a2 - a3 * a3) / (2.0 * a2 * a3);
  if (std::abs(c3raw) > 1.0 + reachSlack_) return std::nullopt;  // out of reach for this (q1, q5)
  const double c3 = std::clamp(c3raw, -1.0, 1.0);
  const Eigen::Vector3d x4 = wrist.c5 * (c6 * n - s6 * o) - wrist.s5 * a;
  const double q234 = std::atan2(x4.z(), x4.x() * c1 + x4.y() * s1);
  const double q3 = (elbow == 0 ? 1.0 : -1.0) * awayFromMergedBranches(std::acos(c3), inside);
  const double q2 = std::atan2(y, x) - std::atan2(a3 * std::sin(q3), a2 + a3 * std::cos(q3));
  Vector6 q;
  q << shoulder.q1, q2, q3, q234 - q2 - q3, wrist.q5, wrist.q6;
  for (auto& v : q) v = wrapToPi(v);
  return q;
}

std::vector<Vector6> UrInverseKinematics::solveBranches(const Eigen::Isometry3d& tipPose,
                                                        double q6AtWristSingularity) const {
  std::vector<Vector6> solutions;
  solutions.reserve(8);
  if (refinedChain_) {
    for (int branch = 0; branch < 8; ++branch) {
      if (auto q = solveBranch(tipPose, branch, q6AtWristSingularity)) solutions.push_back(*q);
    }
    return solutions;
  }
  const TargetFrame target = targetFrame(tipPose);
  for (int shoulderBit = 0; shoulderBit < 2; ++shoulderBit) {
    const auto shoulder = shoulderStep(target, shoulderBit, 0.0);
    if (!shoulder) return solutions;
    for (int wristBit = 0; wristBit < 2; ++wristBit) {
      const WristStep wrist = wristStep(target, *shoulder, wristBit, q6AtWristSingularity, 0.0);
      for (int elbowBit = 0; elbowBit < 2; ++elbowBit) {
        if (auto q = elbowStep(target, *shoulder, wrist, elbowBit, 0.0)) solutions.push_back(*q);
      }
    }
  }
  return solutions;
}

std::optional<Vector6> UrInverseKinematics::analyticBranch(const TargetFrame& target, int branch,
                                                           double q6AtWristSingularity, double inside) const {
  const auto shoulder = shoulderStep(target, branch & 1, inside);
  if (!shoulder) return std::nullopt;
  return elbowStep(target, *shoulder, wristStep(target, *shoulder, (branch >> 1) & 1, q6AtWristSingularity, inside),
                   (branch >> 2) & 1, inside);
}

std::optional<Vector6> UrInverseKinematics::solveBranch(const Eigen::Isometry3d& tipPose, int branch,
                                                        double q6AtWristSingularity) const {
  const TargetFrame target = targetFrame(tipPose);
  if (!refinedChain_) return analyticBranch(target, branch, q6AtWristSingularity, 0.0);
  // Where two branches merge (elbow stretched, wrist or shoulder singular) the pose does not change
  // with that angle to first order, so Newton steps cannot leave it, and near it a step may cross into
  // the other branch: start just inside the branch, and farther inside if the first start crossed.
  for (const double inside : {1e-3, 0.05}) {
    auto q = analyticBranch(target, branch, q6AtWristSingularity, inside);
    if (q && refine(tipPose, *q) && branchOf(*q) == branch) return q;
  }
  return std::nullopt;
}

std::optional<Vector6> UrInverseKinematics::nearestRepresentation(const Vector6& q, const Vector6& reference) const {
  Vector6 result;
  for (int j = 0; j < 6; ++j) {
    // The multiple of 2·pi closest to the reference, then pulled back inside the limits.
    double v = reference[j] + wrapToPi(q[j] - reference[j]);
    if (v > upper_[j]) v -= kTwoPi * std::ceil((v - upper_[j]) / kTwoPi - 1e-12);
    if (v < lower_[j]) v += kTwoPi * std::ceil((lower_[j] - v) / kTwoPi - 1e-12);
    if (v < lower_[j] - 1e-12 || v > upper_[j] + 1e-12) return std::nullopt;
    result[j] = std::clamp(v, lower_[j], upper_[j]);
  }
  return result;
}

std::vector<Vector6> UrInverseKinematics::solveAll(const Eigen::Isometry3d& tipPose) const {
  std::vector<Vector6> all;
  for (const Vector6& branch : solveBranches(tipPose)) {
    // Each joint independently in every representation q + 2·pi·k inside its limits.
    std::vector<std::vector<double>> options(6);
    for (int j = 0; j < 6; ++j) {
      const double first = branch[j] - kTwoPi * std::floor((branch[j] - lower_[j]) / kTwoPi + 1e-12);
      for (double v = first; v <= upper_[j] + 1e-12; v += kTwoPi) {
        if (v >= lower_[j] - 1e-12) options[j].push_back(std::clamp(v, lower_[j], upper_[j]));
      }
    }
    std::size_t combinations = 1;
    for (const auto& o : options) combinations *= o.size();
    for (std::size_t k = 0; k < combinations; ++k) {
      Vector6 q;
      std::size_t rest = k;
      for (int j = 0; j < 6; ++j) {
        q[j] = options[j][rest % options[j].size()];
        rest /= options[j].size();
      }
      all.push_back(q);
    }
  }
  return all;
}

std::optional<Vector6> UrInverseKinematics::solveNearest(const Eigen::Isometry3d& tipPose, const Vector6& seed) const {
  std::optional<Vector6> best;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (const Vector6& branch : solveBranches(tipPose, seed[5])) {
    const auto candidate = nearestRepresentation(branch, seed);
    if (!candidate) continue;
    const double distance = (*candidate - seed).squaredNorm();
    if (distance < bestDistance) {
      bestDistance = distance;
      best = candidate;
    }
  }
  return best;
}

int UrInverseKinematics::branchOf(const Vector6& q) const {
  const Eigen::Isometry3d t06 = urDhForwardKinematics(dh_, q);
  const Eigen::Vector3d p5 = t06.translation() - dh_.d6 * t06.linear().col(2);
  const double psi = std::atan2(p5.y(), p5.x());
  const int shoulder = wrapToPi(q[0] - psi - M_PI_2) >= 0.0 ? 0 : 1;
  const int wrist = std::sin(q[4]) >= 0.0 ? 0 : 1;
  const int elbow = std::sin(q[2]) >= 0.0 ? 0 : 1;
  return shoulder | (wrist << 1) | (elbow << 2);
}

}  // namespace arcplan::robot
