#include "arcplan/report/robot_animation.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/mesh.h"
#include "base64.h"

namespace arcplan::report {
namespace {

std::vector<int> meshedLinks(const robot::RobotModel& model) {
  std::vector<int> links;
  for (std::size_t i = 0; i < model.links().size(); ++i) {
    const auto& collisions = model.links()[i].collisions;
    if (std::any_of(collisions.begin(), collisions.end(), [](const robot::CollisionGeometry& g) {
          return g.shape == robot::CollisionGeometry::Shape::Mesh;
        })) {
      links.push_back(static_cast<int>(i));
    }
  }
  return links;
}

}  // namespace

nlohmann::json robotMeshesJson(const robot::RobotModel& model) {
  nlohmann::json meshes = nlohmann::json::array();
  for (const int index : meshedLinks(model)) {
    const auto& link = model.links()[static_cast<std::size_t>(index)];
    std::vector<float> positions;
    std::vector<std::uint32_t> indices;
    for (const auto& geometry : link.collisions) {
      if (geometry.shape != robot::CollisionGeometry::Shape::Mesh) continue;
      const auto mesh = robot::loadMesh(geometry.meshFile, geometry.meshScale);
      const auto offset = static_cast<std::uint32_t>(positions.size() / 3);
      for (const auto& vertex : mesh.vertices) {
        const Eigen::Vector3d p = geometry.origin * vertex;
        positions.insert(positions.end(),
                         {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
      }
      for (const auto& triangle : mesh.triangles) {
        for (int corner = 0; corner < 3; ++corner)
          indices.push_back(offset + static_cast<std::uint32_t>(triangle[corner]));
      }
    }
    meshes.push_back({{"link", link.name},
                      {"vertices", positions.size() / 3},
                      {"triangles", indices.size() / 3},
                      {"positions", detail::base64Of(positions)},
                      {"indices", detail::base64Of(indices)}});
  }
  return meshes;
}

nlohmann::json linkPoseFrames(const robot::RobotModel& model, const std::vector<double>& times,
                              const std::vector<robot::Vector6>& joints, double rate) {
  if (times.empty() || times.size() != joints.size()) {
    throw Error("link pose frames: " + std::to_string(times.size()) + " times for " + std::to_string(joints.size()) +
                " joint vectors (expected the same non-zero count)");
  }
  if (!(rate > 0.0)) throw Error("link pose frames: rate must be positive");
  const double duration = times.back() - times.front();
  const auto frames = static_cast<std::size_t>(std::floor(duration * rate)) + 1;
  const auto links = meshedLinks(model);
  robot::KinematicsData data(model);
  std::vector<float> poses;
  poses.reserve(frames * links.size() * 7);
  std::size_t segment = 0;
  for (std::size_t frame = 0; frame < frames; ++frame) {
    const double t = std::min(times.front() + static_cast<double>(frame) / rate, times.back());
    while (segment + 2 < times.size() && times[segment + 1] < t) ++segment;
    robot::Vector6 q = joints[segment];
    if (segment + 1 < times.size() && times[segment + 1] > times[segment]) {
      const double s = std::clamp((t - times[segment]) / (times[segment + 1] - times[segment]), 0.0, 1.0);
      q = (1.0 - s) * joints[segment] + s * joints[segment + 1];
    }
    robot::forwardKinematics(model, q, data);
    for (const int link : links) {
      const auto& pose = data.linkPoses[static_cast<std::size_t>(link)];
      const Eigen::Quaterniond rotation(pose.linear());
      const Eigen::Vector3d p = pose.translation();
      poses.insert(poses.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()),
                                 static_cast<float>(rotation.x()), static_cast<float>(rotation.y()),
                                 static_cast<float>(rotation.z()), static_cast<float>(rotation.w())});
    }
  }
  return {{"rate_hz", rate}, {"frames", frames}, {"duration_s", duration}, {"poses", detail::base64Of(poses)}};
}

}  // namespace arcplan::report
