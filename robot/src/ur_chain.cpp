#include "ur_chain.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/SVD>

#include "arcplan/common/error.h"
#include "arcplan/robot/pose.h"

namespace arcplan::robot::detail {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

// Shorter than this, a DH length is treated as zero: the frame cannot be placed there.
constexpr double kDegenerateLength = 1e-3;

Eigen::Vector3d perpendicularPart(const Eigen::Vector3d& v, const Eigen::Vector3d& unitAxis) {
  return v - v.dot(unitAxis) * unitAxis;
}

// Difference of two tip poses as one 6-vector (position, then rotation vector), in the base frame.
Eigen::Matrix<double, 6, 1> poseError(const Eigen::Isometry3d& target, const Eigen::Isometry3d& pose) {
  Eigen::Matrix<double, 6, 1> error;
  const Eigen::AngleAxisd rotation(target.linear() * pose.linear().transpose());
  error << target.translation() - pose.translation(), rotation.angle() * rotation.axis();
  return error;
}

}  // namespace

JointChain jointChainOf(const RobotModel& model) {
  std::vector<int> path;
  for (int link = model.tipLink(); link >= 0; link = model.links()[link].parent) path.push_back(link);
  std::reverse(path.begin(), path.end());
  JointChain chain;
  Eigen::Isometry3d sinceLastJoint = Eigen::Isometry3d::Identity();
  int joints = 0;
  for (const int index : path) {
    const Link& link = model.links()[index];
    sinceLastJoint = sinceLastJoint * link.originInParent;
    if (link.joint < 0) continue;
    if (joints == 6 || link.joint != joints) break;
    chain.origin[joints] = sinceLastJoint;
    chain.axis[joints] = link.axis;
    sinceLastJoint.setIdentity();
    ++joints;
  }
  if (joints != 6 || model.dof() != 6) {
    throw Error("UR inverse kinematics needs a 6-joint chain; '" + model.name() + "' has " +
                std::to_string(model.dof()));
  }
  chain.tip = sinceLastJoint;
  return chain;
}

Eigen::Isometry3d chainTipPose(const JointChain& chain, const Vector6& q,
                               std::array<Eigen::Isometry3d, 6>* jointFrames) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int j = 0; j < 6; ++j) {
    pose = pose * chain.origin[j];
    pose.linear() *= Eigen::AngleAxisd(q[j], chain.axis[j]).toRotationMatrix();
    if (jointFrames) (*jointFrames)[j] = pose;
  }
  return pose * chain.tip;
}

UrChainFit fitUrChain(const JointChain& chain, const std::string& robotName) {
  // Joint axes as lines at q = 0: point P_j (on the axis) and direction Z_j.
  std::array<Eigen::Isometry3d, 6> frames;
  const Eigen::Isometry3d tip = chainTipPose(chain, Vector6::Zero(), &frames);
  Eigen::Vector3d point[6], axis[6];
  for (int j = 0; j < 6; ++j) {
    point[j] = frames[j].translation();
    axis[j] = frames[j].linear() * chain.axis[j];
  }
  const Eigen::Vector3d z0 = axis[0];
  // DH frame 0 on the base axis, level with the base origin, wherever the arm stands in the base frame.
  const Eigen::Vector3d origin0 = point[0] - z0 * z0.dot(point[0]);
  // x0: the upper arm at q = 0 points along -x0 (the UR convention a2 < 0).
  const Eigen::Vector3d upperArm = perpendicularPart(perpendicularPart(point[2] - point[1], axis[1]), z0);
  if (upperArm.norm() < kDegenerateLength)
    throw Error("'" + robotName + "' is not a UR-type arm: elbow axis on the shoulder axis");
  const Eigen::Vector3d x0 = -upperArm.normalized();
  const Eigen::Vector3d y0 = z0.cross(x0);

  UrChainFit fit;
  UrDhParameters& dh = fit.dh;
  dh.d1 = (point[1] - origin0).dot(z0);
  dh.a2 = (point[2] - point[1]).dot(x0);
  dh.a3 = (point[3] - point[2]).dot(x0);
  dh.d4 = -(point[4] - origin0).dot(y0);
  dh.d5 = dh.d1 - (point[5] - origin0).dot(z0);
  // DH frame 6 may sit anywhere on the wrist-3 axis off the wrist-2 axis (the closed form divides by
  // d6): at the wrist-3 joint frame where the description puts it at the flange (UR's ROS 2 files),
  // else where the tip projects onto the axis (ROS 1 files put that frame on the wrist-2 axis).
  const auto d6At = [&](const Eigen::Vector3d& p) {
    return -(point[5] + axis[5] * axis[5].dot(p - point[5]) - origin0).dot(y0) - dh.d4;
  };
  dh.d6 = d6At(point[5]);
  if (std::abs(dh.d6) < kDegenerateLength) dh.d6 = d6At(tip.translation());
  if (std::abs(dh.d6) < kDegenerateLength) {
    throw Error("'" + robotName +
                "': the tip link lies on the wrist-2 axis (d6 = 0); choose tool0 or a tool frame as tip");
  }

  fit.baseToDh0.linear().col(0) = x0;
  fit.baseToDh0.linear().col(1) = y0;
  fit.baseToDh0.linear().col(2) = z0;
  fit.baseToDh0.translation() = origin0;
  fit.dh6ToTip = (fit.baseToDh0 * urDhForwardKinematics(dh, Vector6::Zero())).inverse() * tip;

  // The chain must follow the fitted model everywhere, not only at q = 0.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int trial = 0; trial < 32; ++trial) {
    Vector6 q;
    for (auto& v : q) v = angle(random);
    const Eigen::Isometry3d viaDh = fit.baseToDh0 * urDhForwardKinematics(dh, q) * fit.dh6ToTip;
    const Eigen::Isometry3d actual = chainTipPose(chain, q);
    fit.translationDeviation = std::max(fit.translationDeviation, (viaDh.translation() - actual.translation()).norm());
    fit.rotationDeviation = std::max(fit.rotationDeviation, rotationDistance(viaDh.linear(), actual.linear()));
  }
  return fit;
}

bool refineOnChain(const JointChain& chain, const Eigen::Isometry3d& target, Vector6& q) {
  // Newton steps converge quadratically from a seed within calibration offsets of the solution;
  // at a singularity the SVD gives the smallest step (the free joint combination stays put).
  constexpr double kConverged = 1e-13, kAccepted = 1e-11;
  std::array<Eigen::Isometry3d, 6> frames;
  for (int iteration = 0; iteration < 30; ++iteration) {
    const Eigen::Isometry3d pose = chainTipPose(chain, q, &frames);
    const Eigen::Matrix<double, 6, 1> error = poseError(target, pose);
    if (error.head<3>().norm() < kConverged && error.tail<3>().norm() < kConverged) return true;
    Matrix6 jacobian;
    for (int j = 0; j < 6; ++j) {
      const Eigen::Vector3d z = frames[j].linear() * chain.axis[j];
      jacobian.col(j) << z.cross(pose.translation() - frames[j].translation()), z;
    }
    Eigen::JacobiSVD<Matrix6> svd(jacobian, Eigen::ComputeFullU | Eigen::ComputeFullV);
    svd.setThreshold(1e-10);
    q += svd.solve(error);
  }
  const Eigen::Matrix<double, 6, 1> error = poseError(target, chainTipPose(chain, q));
  return error.head<3>().norm() < kAccepted && error.tail<3>().norm() < kAccepted;
}

}  // namespace arcplan::robot::detail
