#include "arm_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/mesh.h"

namespace arcplan::planners {
namespace {

using robot::CollisionGeometry;

// Outline points of one collision element, in its link's frame.
std::vector<Eigen::Vector3d> outlineOf(const CollisionGeometry& geometry) {
  std::vector<Eigen::Vector3d> local;
  switch (geometry.shape) {
    case CollisionGeometry::Shape::Mesh: {
      const std::vector<Eigen::Vector3d> vertices = robot::loadMesh(geometry.meshFile, geometry.meshScale).vertices;
      const std::size_t stride = std::max<std::size_t>(1, vertices.size() / kOutlinePoints);
      for (std::size_t i = 0; i < vertices.size(); i += stride) local.push_back(vertices[i]);
      break;
    }
    case CollisionGeometry::Shape::Box:
      for (int corner = 0; corner < 8; ++corner) {
        local.emplace_back(Eigen::Vector3d(corner & 1 ? 0.5 : -0.5, corner & 2 ? 0.5 : -0.5, corner & 4 ? 0.5 : -0.5)
                               .cwiseProduct(geometry.boxSize));
      }
      break;
    case CollisionGeometry::Shape::Cylinder:
      for (int k = 0; k < 16; ++k) {
        const double angle = M_PI * k / 4.0;  // two end circles, 8 points each
        local.emplace_back(geometry.radius * std::cos(angle), geometry.radius * std::sin(angle),
                           (k < 8 ? -0.5 : 0.5) * geometry.length);
      }
      break;
    case CollisionGeometry::Shape::Sphere:
      local.emplace_back(Eigen::Vector3d::Zero());
      break;
  }
  for (Eigen::Vector3d& p : local) p = geometry.origin * p;
  return local;
}

double distanceToBox(const Eigen::Vector3d& p, const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  return (low - p).cwiseMax(p - high).cwiseMax(0.0).norm();
}

// The outline point of `link` (world frame) nearest the body (nearest its hull's bounding box first,
// 0 for every point inside it, then nearest its centre) and the side of the body it is on.
ArmContact nearestPoint(const Eigen::Isometry3d& linkPose, const std::vector<Eigen::Vector3d>& outline,
                        const collision::Obstacle& body) {
  const std::vector<Eigen::Vector3d> hull = hullPoints(body);
  Eigen::Vector3d low = hull.front(), high = hull.front();
  for (const Eigen::Vector3d& p : hull) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const Eigen::Vector3d centre = 0.5 * (low + high);
  Eigen::Vector3d best = linkPose.translation();
  double bestScore = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& local : outline) {
    const Eigen::Vector3d p = linkPose * local;
    const double score = distanceToBox(p, low, high) + 1e-3 * (p - centre).norm();
    if (score < bestScore) {
      bestScore = score;
      best = p;
    }
  }
  ArmContact contact;
  contact.offset = best;  // the caller makes it relative to the TCP
  const Eigen::Vector3d outward = best - best.cwiseMax(low).cwiseMin(high);
  contact.side = (outward.norm() > 1e-6 ? outward : Eigen::Vector3d(best - centre)).normalized();
  return contact;
}

}  // namespace

LinkOutlines linkOutlines(const robot::RobotModel& robot) {
  LinkOutlines outlines;
  for (const robot::Link& link : robot.links()) {
    std::vector<Eigen::Vector3d> points;
    for (const CollisionGeometry& geometry : link.collisions) {
      try {
        const std::vector<Eigen::Vector3d> more = outlineOf(geometry);
        points.insert(points.end(), more.begin(), more.end());
      } catch (const Error&) {
        // An unreadable mesh leaves the link its origin (the collision model reports the file itself).
      }
    }
    if (points.empty()) points.emplace_back(Eigen::Vector3d::Zero());
    outlines.push_back(std::move(points));
  }
  return outlines;
}

std::vector<ArmContact> armContacts(const robot::RobotModel& robot, const LinkOutlines& outlines,
                                    const robot::Vector6& q,
                                    const std::vector<std::pair<std::string, std::string>>& pairs,
                                    const std::vector<collision::Obstacle>& bodies) {
  robot::KinematicsData kinematics(robot);
  robot::forwardKinematics(robot, q, kinematics);
  const Eigen::Vector3d tcp = kinematics.linkPoses[static_cast<std::size_t>(robot.tipLink())].translation();
  std::vector<ArmContact> contacts;
  for (const auto& [linkName, bodyName] : pairs) {
    const auto link = std::find_if(robot.links().begin(), robot.links().end(),
                                   [&](const robot::Link& l) { return l.name == linkName; });
    const auto body =
        std::find_if(bodies.begin(), bodies.end(), [&](const collision::Obstacle& b) { return b.name == bodyName; });
    if (link == robot.links().end() || body == bodies.end()) continue;
    if (std::any_of(contacts.begin(), contacts.end(), [&](const ArmContact& c) { return c.link == linkName; }))
      continue;
    const auto index = static_cast<std::size_t>(link - robot.links().begin());
    ArmContact contact = nearestPoint(kinematics.linkPoses[index], outlines.at(index), *body);
    contact.link = linkName;
    contact.offset -= tcp;
    for (const Eigen::Vector3d& local : outlines.at(index))
      contact.outline.push_back(kinematics.linkPoses[index] * local - tcp);
    if (contact.offset.norm() > kArmContactReach) contacts.push_back(std::move(contact));
  }
  return contacts;
}

ObstacleCluster seenFromTheTcp(const ObstacleCluster& cluster, const std::vector<Eigen::Vector3d>& link) {
  ObstacleCluster shifted = cluster;
  shifted.hull.clear();
  for (const Eigen::Vector3d& h : cluster.hull) {
    for (const Eigen::Vector3d& l : link) shifted.hull.push_back(h - l);
  }
  return shifted;
}

}  // namespace arcplan::planners
