#include "arcplan/report/robot_animation.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/mesh.h"
#include "arcplan/robot/primitive_mesh.h"
#include "base64.h"
#include "drawn_meshes.h"

namespace arcplan::report {
namespace {

// Links with any collision geometry: the arm's links, and the tool, sensor and gripper beyond the flange.
std::vector<int> drawnLinks(const robot::RobotModel& model) {
  std::vector<int> links;
  for (std::size_t i = 0; i < model.links().size(); ++i) {
    if (!model.links()[i].collisions.empty()) links.push_back(static_cast<int>(i));
  }
  return links;
}

// Facets around a drawn cylinder: round enough at report scale, fewer triangles than the default.
constexpr int kCylinderSegments = 24;

// The geometry in its own frame. A URDF may give a primitive no volume (urdfdom accepts a zero
// radius); it draws nothing rather than ending the report.
robot::TriangleMesh geometryMesh(const robot::CollisionGeometry& geometry) {
  using Shape = robot::CollisionGeometry::Shape;
  switch (geometry.shape) {
    case Shape::Box:
      if (!(geometry.boxSize.minCoeff() > 0.0)) return {};
      return robot::boxMesh(geometry.boxSize);
    case Shape::Sphere:
      if (!(geometry.radius > 0.0)) return {};
      return robot::sphereMesh(geometry.radius);
    case Shape::Cylinder:
      if (!(geometry.radius > 0.0 && geometry.length > 0.0)) return {};
      return robot::cylinderMesh(Eigen::Vector3d(0.0, 0.0, -geometry.length / 2.0),
                                 Eigen::Vector3d(0.0, 0.0, geometry.length / 2.0), geometry.radius, kCylinderSegments);
    case Shape::Mesh:
      break;
  }
  return robot::loadMesh(geometry.meshFile, geometry.meshScale);
}

}  // namespace

nlohmann::json robotMeshesJson(const robot::RobotModel& model, std::size_t maxTrianglesPerLink) {
  nlohmann::json meshes = nlohmann::json::array();
  for (const int index : drawnLinks(model)) {
    const auto& link = model.links()[static_cast<std::size_t>(index)];
    robot::TriangleMesh merged;  // every geometry of the link, in the link frame
    for (const auto& geometry : link.collisions) {
      auto mesh = geometryMesh(geometry);
      for (auto& vertex : mesh.vertices) vertex = geometry.origin * vertex;
      robot::appendMesh(merged, mesh);
    }
    const auto drawn = detail::withAtMostTriangles(merged, maxTrianglesPerLink);
    auto json = detail::meshJson(drawn);
    json["link"] = link.name;
    json["source_triangles"] = merged.triangles.size();
    meshes.push_back(std::move(json));
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
  const auto links = drawnLinks(model);
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
