#include "arcplan/trajectory/path_densification.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"

namespace arcplan::trajectory {
namespace {

void requirePositive(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw Error(std::string("path densification: ") + name + " must be a positive finite number, got " +
                std::to_string(value));
  }
}

}  // namespace

DensePath densifyJointPath(const robot::RobotModel& model, const JointPath& path, const DensificationOptions& options) {
  requirePositive(options.maxJointStep, "maxJointStep (rad)");
  requirePositive(options.maxTcpStep, "maxTcpStep (m)");
  if (path.size() < 2) throw Error("path densification: a path needs at least 2 waypoints, got " + std::to_string(path.size()));

  robot::KinematicsData kinematics(model);
  const auto tcpOf = [&](const robot::Vector6& q) {
    robot::forwardKinematics(model, q, kinematics);
    return Eigen::Vector3d(kinematics.linkPoses[model.tipLink()].translation());
  };

  DensePath dense;
  dense.waypoints.reserve(path.size());
  dense.tcpPositions.reserve(path.size());
  dense.waypoints.push_back(path.front());
  dense.tcpPositions.push_back(tcpOf(path.front()));

  std::vector<Eigen::Vector3d> pieceTcp;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const robot::Vector6 start = path[i];
    const robot::Vector6 step = path[i + 1] - start;
    if (step.cwiseAbs().maxCoeff() == 0.0) continue;  // an exact repeat adds no motion
    long pieces = std::max(1L, static_cast<long>(std::ceil(step.cwiseAbs().maxCoeff() / options.maxJointStep)));
    // The TCP chord of a piece is only known after FK: refine until every chord is short enough.
    while (true) {
      pieceTcp.clear();
      double longestChord = 0.0;
      Eigen::Vector3d previous = dense.tcpPositions.back();
      for (long p = 1; p <= pieces; ++p) {
        const Eigen::Vector3d tcp = tcpOf(p == pieces ? path[i + 1] : robot::Vector6(start + step * (double(p) / pieces)));
        longestChord = std::max(longestChord, (tcp - previous).norm());
        pieceTcp.push_back(tcp);
        previous = tcp;
      }
      if (longestChord <= options.maxTcpStep) break;
      pieces = std::max(pieces + 1, static_cast<long>(std::ceil(pieces * longestChord / options.maxTcpStep)));
    }
    for (long p = 1; p <= pieces; ++p) {
      dense.waypoints.push_back(p == pieces ? path[i + 1] : robot::Vector6(start + step * (double(p) / pieces)));
      dense.tcpPositions.push_back(pieceTcp[p - 1]);
    }
  }
  if (dense.waypoints.size() < 2) throw Error("path densification: all waypoints of the path are the same configuration");

  dense.tcpArcLength.resize(dense.tcpPositions.size());
  dense.tcpArcLength[0] = 0.0;
  for (std::size_t k = 1; k < dense.tcpPositions.size(); ++k) {
    dense.tcpArcLength[k] = dense.tcpArcLength[k - 1] + (dense.tcpPositions[k] - dense.tcpPositions[k - 1]).norm();
  }
  return dense;
}

}  // namespace arcplan::trajectory
