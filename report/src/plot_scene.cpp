#include "plot_scene.h"

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "arcplan/common/error.h"
#include "arcplan/report/robot_animation.h"
#include "drawn_meshes.h"

namespace arcplan::report::detail {
namespace {

// Mesh shapes carry their triangles in scene.json as plain lists: on the page they travel like the
// link meshes (base64, thinned when large).
void encodeMesh(nlohmann::json& shape) {
  if (shape.value("shape", "") != "mesh" || !shape.contains("vertices")) return;
  const auto vertices = shape["vertices"].get<std::vector<double>>();
  const auto corners = shape["triangles"].get<std::vector<int>>();
  if (vertices.size() % 3 != 0 || corners.size() % 3 != 0)
    throw Error("scene.json: obstacle '" + shape.value("name", "") + "': " + std::to_string(vertices.size()) +
                " vertex coordinates and " + std::to_string(corners.size()) +
                " triangle corners; expected multiples of 3");
  robot::TriangleMesh mesh;
  for (std::size_t i = 0; i + 2 < vertices.size(); i += 3)
    mesh.vertices.emplace_back(vertices[i], vertices[i + 1], vertices[i + 2]);
  for (std::size_t i = 0; i + 2 < corners.size(); i += 3) {
    const Eigen::Vector3i triangle(corners[i], corners[i + 1], corners[i + 2]);
    if (triangle.minCoeff() < 0 || triangle.maxCoeff() >= static_cast<int>(mesh.vertices.size()))
      throw Error("scene.json: obstacle '" + shape.value("name", "") + "': triangle " + std::to_string(i / 3) +
                  " names a vertex that is not there");
    mesh.triangles.push_back(triangle);
  }
  shape.erase("vertices");
  shape.erase("triangles");
  shape["source_triangles"] = mesh.triangles.size();
  shape.update(meshJson(withAtMostTriangles(mesh, kMaxTrianglesPerMesh)));
}

Eigen::Isometry3d poseOf(const nlohmann::json& shape) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 3; ++i) {
    pose.translation()[i] = shape.at("position").at(i).get<double>();
    for (int j = 0; j < 3; ++j) pose.linear()(i, j) = shape.at("rotation").at(i).at(j).get<double>();
  }
  return pose;
}

void setPose(nlohmann::json& shape, const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d r = pose.linear();
  const Eigen::Vector3d t = pose.translation();
  shape["position"] = {t.x(), t.y(), t.z()};
  shape["rotation"] = {{r(0, 0), r(0, 1), r(0, 2)}, {r(1, 0), r(1, 1), r(1, 2)}, {r(2, 0), r(2, 1), r(2, 2)}};
}

// The drawn link `link` hangs from (itself when it has geometry) and its frame in that link's, or
// nullopt when a moving joint comes first or the robot has no such link.
std::optional<std::pair<int, Eigen::Isometry3d>> drawnAncestor(const robot::RobotModel& robot,
                                                               const std::string& link) {
  int index = -1;
  for (std::size_t i = 0; i < robot.links().size(); ++i) {
    if (robot.links()[i].name == link) index = static_cast<int>(i);
  }
  Eigen::Isometry3d inAncestor = Eigen::Isometry3d::Identity();
  while (index >= 0 && robot.links()[static_cast<std::size_t>(index)].collisions.empty()) {
    const auto& current = robot.links()[static_cast<std::size_t>(index)];
    if (current.joint >= 0) return std::nullopt;  // its pose in the parent's frame changes with q
    inAncestor = current.originInParent * inAncestor;
    index = current.parent;
  }
  if (index < 0) return std::nullopt;
  return std::make_pair(index, inAncestor);
}

}  // namespace

robot::RobotSource robotSourceOf(const nlohmann::json& scene) {
  robot::RobotSource source;
  if (!scene.contains("robot")) return source;
  const auto& json = scene.at("robot");
  source.urdf = json.value("urdf", "");
  source.urType = json.value("ur_type", "");
  source.description = json.value("description", "");
  source.kinematics = json.value("kinematics", "");
  source.chain.baseLink = json.value("base_link", source.chain.baseLink);
  source.chain.tipLink = json.value("tip_link", source.chain.tipLink);
  if (json.contains("tcp_offset") && json["tcp_offset"].is_array()) {
    const auto& v = json["tcp_offset"];
    Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
    offset.translation() = Eigen::Vector3d(v.at(0), v.at(1), v.at(2));
    offset.linear() = Eigen::Quaterniond(v.at(6), v.at(3), v.at(4), v.at(5)).normalized().toRotationMatrix();
    source.chain.tcpOffset = offset;
  }
  return source;
}

robot::Vector6 jointsOf(const nlohmann::json& scene, const char* key) {
  const auto values = scene.at(key).get<std::vector<double>>();
  if (values.size() != 6)
    throw Error(std::string("scene.json: ") + key + " has " + std::to_string(values.size()) + " values, expected 6");
  return Eigen::Map<const robot::Vector6>(values.data());
}

nlohmann::json drawnScene(nlohmann::json scene, const robot::RobotModel* robot) {
  for (auto& obstacle : scene["obstacles"]) encodeMesh(obstacle);
  nlohmann::json attached = nlohmann::json::array();
  for (auto& body : scene.value("attached", nlohmann::json::array())) {
    const auto ancestor = robot ? drawnAncestor(*robot, body.value("link", "")) : std::nullopt;
    if (!ancestor) continue;
    encodeMesh(body);
    setPose(body, ancestor->second * poseOf(body));
    body["link"] = robot->links()[static_cast<std::size_t>(ancestor->first)].name;
    attached.push_back(std::move(body));
  }
  scene["attached"] = std::move(attached);
  return scene;
}

}  // namespace arcplan::report::detail
