#include "arcplan/robot/ur_inverse_kinematics.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "arcplan/common/error.h"

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

Eigen::Vector3d perpendicularPart(const Eigen::Vector3d& v, const Eigen::Vector3d& unitAxis) {
  return v - v.dot(unitAxis) * unitAxis;
}

}  // namespace

Eigen::Isometry3d urDhForwardKinematics(const UrDhParameters& dh, const Vector6& q) {
  return dhLink(q[0], dh.d1, 0.0, M_PI_2) * dhLink(q[1], 0.0, dh.a2, 0.0) * dhLink(q[2], 0.0, dh.a3, 0.0) *
         dhLink(q[3], dh.d4, 0.0, M_PI_2) * dhLink(q[4], dh.d5, 0.0, -M_PI_2) * dhLink(q[5], dh.d6, 0.0, 0.0);
}

UrInverseKinematics::UrInverseKinematics(const RobotModel& model) {
  if (model.dof() != 6) {
    throw Error("UR inverse kinematics needs a 6-joint chain; '" + model.name() + "' has " +
                std::to_string(model.dof()));
  }
  for (int j = 0; j < 6; ++j) {
    lower_[j] = model.joints()[j].limits.lower;
    upper_[j] = model.joints()[j].limits.upper;
  }
  // Joint axes as lines at q = 0: point P_j (on the axis) and direction Z_j.
  KinematicsData data(model);
  forwardKinematics(model, Vector6::Zero(), data);
  Eigen::Vector3d point[6], axis[6];
  for (int j = 0; j < 6; ++j) {
    const int link = model.joints()[j].link;
    point[j] = data.linkPoses[link].translation();
    axis[j] = data.linkPoses[link].linear() * model.links()[link].axis;
  }
  const Eigen::Vector3d z0 = axis[0];
  const Eigen::Vector3d origin0 = z0 * z0.dot(data.linkPoses[0].translation());  // base origin on axis 0
  // x0: the upper arm at q = 0 points along -x0 (the UR convention a2 < 0).
  const Eigen::Vector3d upperArm = perpendicularPart(perpendicularPart(point[2] - point[1], axis[1]), z0);
  if (upperArm.norm() < 1e-6)
    throw Error("'" + model.name() + "' is not a UR-type arm: elbow axis on the shoulder axis");
  const Eigen::Vector3d x0 = -upperArm.normalized();
  const Eigen::Vector3d y0 = z0.cross(x0);

  dh_.d1 = (point[1] - origin0).dot(z0);
  dh_.a2 = (point[2] - point[1]).dot(x0);
  dh_.a3 = (point[3] - point[2]).dot(x0);
  dh_.d4 = -(point[4] - origin0).dot(y0);
  dh_.d5 = dh_.d1 - (point[5] - origin0).dot(z0);
  // Frame 6 sits where the tip projects onto the last axis, so a tool frame further out works too.
  const Eigen::Vector3d tip = data.linkPoses[model.tipLink()].translation();
  const Eigen::Vector3d flange = point[5] + axis[5] * axis[5].dot(tip - point[5]);
  dh_.d6 = -(flange - origin0).dot(y0) - dh_.d4;
  if (std::abs(dh_.d6) < 1e-6) {
    throw Error("'" + model.name() +
                "': the tip link lies on the wrist-2 axis (d6 = 0); choose tool0 or a tool frame as tip");
  }

  baseToDh0_.linear().col(0) = x0;
  baseToDh0_.linear().col(1) = y0;
  baseToDh0_.linear().col(2) = z0;
  baseToDh0_.translation() = origin0;
  dh6ToTip_ = (baseToDh0_ * urDhForwardKinematics(dh_, Vector6::Zero())).inverse() * data.linkPoses[model.tipLink()];
  dh0ToBase_ = baseToDh0_.inverse();
  tipToDh6_ = dh6ToTip_.inverse();

  // The chain must reproduce the DH model everywhere, not only at q = 0.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int trial = 0; trial < 32; ++trial) {
    Vector6 q;
    for (auto& v : q) v = angle(random);
    forwardKinematics(model, q, data);
    const Eigen::Isometry3d viaDh = baseToDh0_ * urDhForwardKinematics(dh_, q) * dh6ToTip_;
    const double error = (viaDh.matrix() - data.linkPoses[model.tipLink()].matrix()).norm();
    if (error > 1e-8) {
      std::ostringstream message;
      message << "'" << model.name() << "' is not a UR-type arm (the chain differs from its DH model by " << error
              << " at a test configuration)";
      throw Error(message.str());
    }
  }
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
                                                                                   int shoulder) const {
  // The wrist-2 centre lies at distance d4 from the vertical arm plane.
  const Eigen::Vector3d p5 = target.p - dh_.d6 * target.a;
  const double rho = std::hypot(p5.x(), p5.y());
  if (rho < std::abs(dh_.d4) * (1.0 - 1e-12)) return std::nullopt;
  const double phi = std::acos(std::clamp(dh_.d4 / rho, -1.0, 1.0));
  const double q1 = std::atan2(p5.y(), p5.x()) + M_PI_2 + (shoulder == 0 ? phi : -phi);
  return ShoulderStep{q1, std::sin(q1), std::cos(q1)};
}

UrInverseKinematics::WristStep UrInverseKinematics::wristStep(const TargetFrame& target, const ShoulderStep& shoulder,
                                                              int wrist, double q6AtWristSingularity) const {
  const auto& [n, o, a, p] = target;
  const double s1 = shoulder.s1, c1 = shoulder.c1;
  // q5 from the tool point's offset from the arm plane.
  const double c5 = std::clamp((p.x() * s1 - p.y() * c1 - dh_.d4) / dh_.d6, -1.0, 1.0);
  const double q5 = (wrist == 0 ? 1.0 : -1.0) * std::acos(c5);
  const double s5 = std::sin(q5);
  double q6 = q6AtWristSingularity;
  if (std::abs(s5) > kSingularityTolerance) {
    q6 = std::atan2(-(o.x() * s1 - o.y() * c1) / s5, (n.x() * s1 - n.y() * c1) / s5);
  }
  return {q5, s5, c5, q6, std::sin(q6), std::cos(q6)};
}

std::optional<Vector6> UrInverseKinematics::elbowStep(const TargetFrame& target, const ShoulderStep& shoulder,
                                                      const WristStep& wrist, int elbow) const {
  const auto& [n, o, a, p] = target;
  const auto& [d1, a2, a3, d4, d5, d6] = dh_;
  const double s1 = shoulder.s1, c1 = shoulder.c1, s6 = wrist.s6, c6 = wrist.c6;
  // Planar 3R for q2, q3, q4 in the arm plane.
  const Eigen::Vector3d p4 = p - d6 * a + d5 * (s6 * n + c6 * o);
  const double x = p4.x() * c1 + p4.y() * s1;
  const double y = p4.z() - d1;
  const double c3raw = (x * x + y * y - a2 * a2 - a3 * a3) / (2.0 * a2 * a3);
  if (std::abs(c3raw) > 1.0 + 1e-9) return std::nullopt;  // out of reach for this (q1, q5)
  const double c3 = std::clamp(c3raw, -1.0, 1.0);
  const Eigen::Vector3d x4 = wrist.c5 * (c6 * n - s6 * o) - wrist.s5 * a;
  const double q234 = std::atan2(x4.z(), x4.x() * c1 + x4.y() * s1);
  const double q3 = (elbow == 0 ? 1.0 : -1.0) * std::acos(c3);
  const double q2 = std::atan2(y, x) - std::atan2(a3 * std::sin(q3), a2 + a3 * c3);
  Vector6 q;
  q << shoulder.q1, q2, q3, q234 - q2 - q3, wrist.q5, wrist.q6;
  for (auto& v : q) v = wrapToPi(v);
  return q;
}

std::vector<Vector6> UrInverseKinematics::solveBranches(const Eigen::Isometry3d& tipPose,
                                                        double q6AtWristSingularity) const {
  const TargetFrame target = targetFrame(tipPose);
  std::vector<Vector6> solutions;
  solutions.reserve(8);
  for (int shoulderBit = 0; shoulderBit < 2; ++shoulderBit) {
    const auto shoulder = shoulderStep(target, shoulderBit);
    if (!shoulder) return solutions;
    for (int wristBit = 0; wristBit < 2; ++wristBit) {
      const WristStep wrist = wristStep(target, *shoulder, wristBit, q6AtWristSingularity);
      for (int elbowBit = 0; elbowBit < 2; ++elbowBit) {
        if (auto q = elbowStep(target, *shoulder, wrist, elbowBit)) solutions.push_back(*q);
      }
    }
  }
  return solutions;
}

std::optional<Vector6> UrInverseKinematics::solveBranch(const Eigen::Isometry3d& tipPose, int branch,
                                                        double q6AtWristSingularity) const {
  const TargetFrame target = targetFrame(tipPose);
  const auto shoulder = shoulderStep(target, branch & 1);
  if (!shoulder) return std::nullopt;
  return elbowStep(target, *shoulder, wristStep(target, *shoulder, (branch >> 1) & 1, q6AtWristSingularity),
                   (branch >> 2) & 1);
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
