#include "arcplan/collision/scene.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <set>

#include "arcplan/collision/allowed_collisions.h"
#include "arcplan/common/error.h"
#include "arcplan/common/yaml_reading.h"
#include "arcplan/robot/package_path.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/robot_source.h"

namespace arcplan::collision {
namespace {

const robot::TriangleMesh& meshOf(const Obstacle& obstacle, std::shared_ptr<const robot::TriangleMesh>& loaded) {
  if (obstacle.meshData) return *obstacle.meshData;
  loaded = std::make_shared<const robot::TriangleMesh>(robot::loadMesh(obstacle.meshFile, obstacle.meshScale));
  return *loaded;
}

// Centre of the mesh's axis-aligned box in the obstacle frame.
Eigen::Vector3d localMeshCenter(const robot::TriangleMesh& mesh) {
  Eigen::Vector3d lower = Eigen::Vector3d::Constant(INFINITY), upper = -lower;
  for (const auto& v : mesh.vertices) {
    lower = lower.cwiseMin(v);
    upper = upper.cwiseMax(v);
  }
  return (lower + upper) / 2.0;
}

// Reads one scene file; every message starts with "file:line:column: field".
class SceneReader {
public:
  explicit SceneReader(const std::filesystem::path& file) : yaml_(file) {}

  Scene read() {
    const YAML::Node root = yaml_.load("scene file");
    if (!root.IsMap()) {
      yaml_.fail(root, "scene", "expected a mapping with keys name, robot, obstacles, allowed_collisions, queries");
    }
    yaml_.checkKeys(root, "scene", {"name", "description", "robot", "obstacles", "allowed_collisions", "queries"});

    Scene scene;
    scene.sourceFile = yaml_.file();
    scene.name = root["name"] ? yaml_.text(root["name"], "name") : yaml_.file().stem().string();
    readRobot(root["robot"], scene);
    if (const auto obstacles = root["obstacles"]) {
      yaml_.expectSequence(obstacles, "obstacles");
      for (std::size_t i = 0; i < obstacles.size(); ++i) {
        scene.obstacles.push_back(readObstacle(obstacles[i], "obstacles[" + std::to_string(i) + "]"));
      }
      checkObstacleNames(obstacles, scene);
    }
    if (const auto pairs = root["allowed_collisions"]) readAllowedCollisions(pairs, scene);
    if (const auto queries = root["queries"]) {
      yaml_.expectSequence(queries, "queries");
      std::set<std::string> names;
      for (std::size_t i = 0; i < queries.size(); ++i) {
        const std::string field = "queries[" + std::to_string(i) + "]";
        scene.queries.push_back(readQuery(queries[i], field));
        if (!names.insert(scene.queries.back().name).second) {
          yaml_.fail(queries[i], field + ".name", "duplicate query name '" + scene.queries.back().name + "'");
        }
      }
    }
    return scene;
  }

private:
  Eigen::Vector3d positiveVector(const YAML::Node& node, const std::string& field) const {
    const auto values = yaml_.positives(node, field, 3);
    return {values[0], values[1], values[2]};
  }

  robot::Vector6 vector6(const YAML::Node& node, const std::string& field) const {
    const auto values = yaml_.numbers(node, field, 6);
    return Eigen::Map<const robot::Vector6>(values.data());
  }

  void readRobot(const YAML::Node& node, Scene& scene) {
    if (!node) {
      linkNames_ = linkNamesOf(robot::ur10e());
      return;
    }
    if (node.IsScalar()) {
      if (node.Scalar() != "ur10e") {
        yaml_.fail(
            node, "robot",
            "expected 'ur10e' (built in) or a mapping {urdf: FILE} or {ur_type: TYPE}, got '" + node.Scalar() + "'");
      }
      linkNames_ = linkNamesOf(robot::ur10e());
      return;
    }
    yaml_.expectMap(node, "robot");
    yaml_.checkKeys(node, "robot", {"urdf", "ur_type", "description", "kinematics", "srdf", "tcp"});
    robot::RobotSource& source = scene.robot;
    if (node["urdf"] && node["ur_type"]) yaml_.fail(node, "robot", "give either urdf or ur_type, not both");
    if (const auto urdf = node["urdf"]) {
      source.urdf = existingPath(urdf, "robot.urdf", "URDF file");
      for (const char* key : {"description", "kinematics"}) {
        if (node[key]) yaml_.fail(node[key], std::string("robot.") + key, "only a robot given by ur_type has it");
      }
    } else if (const auto type = node["ur_type"]) {
      source.urType = yaml_.text(type, "robot.ur_type");
      if (const auto folder = node["description"])
        source.description = existingPath(folder, "robot.description", "folder");
      if (const auto file = node["kinematics"]) source.kinematics = existingPath(file, "robot.kinematics", "file");
    } else {
      yaml_.fail(node, "robot", "missing 'urdf' or 'ur_type'");
    }
    if (const auto tcp = node["tcp"]) readTcp(tcp, source.chain);
    if (const auto srdf = node["srdf"]) source.srdf = existingPath(srdf, "robot.srdf", "SRDF file");
    const auto where = node["ur_type"] ? node["ur_type"] : node["urdf"];
    try {
      const robot::RobotModel model = robot::loadRobot(source);
      linkNames_ = linkNamesOf(model);
      if (!source.srdf.empty()) srdfAllowedCollisions(source.srdf, model);  // every pair names a link of it
    } catch (const Error& e) {
      yaml_.fail(where, "robot", e.what());
    }
  }

  // `tcp: LINK` or `tcp: {link: LINK, offset: [x, y, z, roll, pitch, yaw]}` (link default tool0).
  void readTcp(const YAML::Node& node, robot::ChainSelection& chain) const {
    if (node.IsScalar()) {
      chain.tipLink = yaml_.text(node, "robot.tcp");
      return;
    }
    yaml_.checkKeys(node, "robot.tcp", {"link", "offset"});
    if (const auto link = node["link"]) chain.tipLink = yaml_.text(link, "robot.tcp.link");
    if (const auto offset = node["offset"]) {
      const auto values = yaml_.numbers(offset, "robot.tcp.offset", 6);
      chain.tcpOffset = robot::poseFromXyzRpy({values[0], values[1], values[2], values[3], values[4], values[5]});
    }
  }

  // A file or folder named relative to the scene file; it must exist.
  std::filesystem::path existingPath(const YAML::Node& node, const std::string& field, const std::string& what) const {
    std::filesystem::path path = yaml_.text(node, field);
    if (path.is_relative()) path = yaml_.file().parent_path() / path;
    if (!std::filesystem::exists(path)) yaml_.fail(node, field, what + " " + path.string() + " does not exist");
    return path;
  }

  static std::set<std::string> linkNamesOf(const robot::RobotModel& model) {
    std::set<std::string> names;
    for (const auto& link : model.links()) names.insert(link.name);
    return names;
  }

  Obstacle readObstacle(const YAML::Node& node, const std::string& field) const {
    yaml_.expectMap(node, field);
    yaml_.checkKeys(node, field, {"name", "sphere", "box", "cylinder", "mesh", "position", "rpy"});
    Obstacle obstacle;
    obstacle.name = yaml_.text(yaml_.required(node, "name", field), field + ".name");
    const std::string named = field + " ('" + obstacle.name + "')";

    int shapes = 0;
    for (const char* key : {"sphere", "box", "cylinder", "mesh"}) shapes += node[key] ? 1 : 0;
    if (shapes != 1) {
      yaml_.fail(node, named,
                 shapes == 0 ? "no shape: expected one of sphere, box, cylinder, mesh"
                             : "more than one shape: give exactly one of sphere, box, cylinder, mesh");
    }
    if (const auto sphere = node["sphere"]) {
      yaml_.expectMap(sphere, named + ".sphere");
      yaml_.checkKeys(sphere, named + ".sphere", {"radius"});
      obstacle.shape = Obstacle::Shape::Sphere;
      obstacle.radius = yaml_.positive(yaml_.required(sphere, "radius", named + ".sphere"), named + ".sphere.radius");
    } else if (const auto box = node["box"]) {
      yaml_.expectMap(box, named + ".box");
      yaml_.checkKeys(box, named + ".box", {"size"});
      obstacle.shape = Obstacle::Shape::Box;
      obstacle.size = positiveVector(yaml_.required(box, "size", named + ".box"), named + ".box.size");
    } else if (const auto cylinder = node["cylinder"]) {
      yaml_.expectMap(cylinder, named + ".cylinder");
      yaml_.checkKeys(cylinder, named + ".cylinder", {"radius", "length"});
      obstacle.shape = Obstacle::Shape::Cylinder;
      obstacle.radius =
          yaml_.positive(yaml_.required(cylinder, "radius", named + ".cylinder"), named + ".cylinder.radius");
      obstacle.length =
          yaml_.positive(yaml_.required(cylinder, "length", named + ".cylinder"), named + ".cylinder.length");
    } else {
      const auto mesh = node["mesh"];
      yaml_.expectMap(mesh, named + ".mesh");
      yaml_.checkKeys(mesh, named + ".mesh", {"file", "scale"});
      obstacle.shape = Obstacle::Shape::Mesh;
      const auto fileNode = yaml_.required(mesh, "file", named + ".mesh");
      if (const auto scale = mesh["scale"]) {
        obstacle.meshScale = scale.IsSequence()
                                 ? positiveVector(scale, named + ".mesh.scale")
                                 : Eigen::Vector3d::Constant(yaml_.positive(scale, named + ".mesh.scale"));
      }
      try {
        obstacle.meshFile = robot::resolveResourceUri(yaml_.text(fileNode, named + ".mesh.file"), yaml_.file());
        obstacle.meshData =
            std::make_shared<const robot::TriangleMesh>(robot::loadMesh(obstacle.meshFile, obstacle.meshScale));
      } catch (const Error& e) {
        yaml_.fail(fileNode, named + ".mesh.file", e.what());
      }
    }

    const auto position = yaml_.numbers(yaml_.required(node, "position", named), named + ".position", 3);
    std::array<double, 6> xyzRpy{position[0], position[1], position[2], 0.0, 0.0, 0.0};
    if (const auto rpy = node["rpy"]) {
      const auto angles = yaml_.numbers(rpy, named + ".rpy", 3);
      std::copy(angles.begin(), angles.end(), xyzRpy.begin() + 3);
    }
    obstacle.pose = robot::poseFromXyzRpy(xyzRpy);
    return obstacle;
  }

  void checkObstacleNames(const YAML::Node& obstacles, const Scene& scene) const {
    std::set<std::string> names;
    for (std::size_t i = 0; i < scene.obstacles.size(); ++i) {
      const std::string& name = scene.obstacles[i].name;
      const std::string field = "obstacles[" + std::to_string(i) + "].name";
      if (linkNames_.count(name)) yaml_.fail(obstacles[i], field, "'" + name + "' is already the name of a robot link");
      if (!names.insert(name).second) yaml_.fail(obstacles[i], field, "duplicate obstacle name '" + name + "'");
    }
  }

  void readAllowedCollisions(const YAML::Node& pairs, Scene& scene) const {
    yaml_.expectSequence(pairs, "allowed_collisions");
    std::set<std::string> known = linkNames_;
    for (const auto& obstacle : scene.obstacles) known.insert(obstacle.name);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const std::string field = "allowed_collisions[" + std::to_string(i) + "]";
      const auto pair = pairs[i];
      if (!pair.IsSequence() || pair.size() != 2)
        yaml_.fail(pair, field, "expected a pair [name, name] of links or obstacles");
      std::array<std::string, 2> names;
      for (std::size_t k = 0; k < 2; ++k) {
        names[k] = yaml_.text(pair[k], field + "[" + std::to_string(k) + "]");
        if (!known.count(names[k])) {
          std::string list;
          for (const auto& name : known) list += (list.empty() ? "" : ", ") + name;
          yaml_.fail(pair[k], field, "unknown link or obstacle '" + names[k] + "'; known: " + list);
        }
      }
      scene.allowedCollisions.emplace_back(names[0], names[1]);
    }
  }

  QueryEndpoint readEndpoint(const YAML::Node& node, const std::string& field) const {
    yaml_.expectMap(node, field);
    yaml_.checkKeys(node, field, {"pose", "seed", "joints"});
    QueryEndpoint endpoint;
    const bool hasPose = static_cast<bool>(node["pose"]), hasJoints = static_cast<bool>(node["joints"]);
    if (hasPose == hasJoints)
      yaml_.fail(node, field, "expected exactly one of 'pose' (with optional 'seed') or 'joints'");
    if (hasPose) {
      const auto values = yaml_.numbers(node["pose"], field + ".pose", 6);
      endpoint.pose = std::array<double, 6>{values[0], values[1], values[2], values[3], values[4], values[5]};
      if (const auto seed = node["seed"]) endpoint.seed = vector6(seed, field + ".seed");
    } else {
      if (node["seed"]) yaml_.fail(node["seed"], field + ".seed", "a seed only chooses the IK branch of a 'pose'");
      endpoint.joints = vector6(node["joints"], field + ".joints");
    }
    return endpoint;
  }

  Query readQuery(const YAML::Node& node, const std::string& field) const {
    yaml_.expectMap(node, field);
    yaml_.checkKeys(node, field, {"name", "start", "goal"});
    Query query;
    query.name = yaml_.text(yaml_.required(node, "name", field), field + ".name");
    query.start = readEndpoint(yaml_.required(node, "start", field), field + ".start");
    query.goal = readEndpoint(yaml_.required(node, "goal", field), field + ".goal");
    return query;
  }

  YamlReader yaml_;
  std::set<std::string> linkNames_;
};

}  // namespace

Eigen::Vector3d Obstacle::boundingCenter() const {
  if (shape != Shape::Mesh) return pose.translation();
  std::shared_ptr<const robot::TriangleMesh> loaded;
  return pose * localMeshCenter(meshOf(*this, loaded));
}

double Obstacle::boundingRadius() const {
  switch (shape) {
    case Shape::Sphere:
      return radius;
    case Shape::Box:
      return size.norm() / 2.0;
    case Shape::Cylinder:
      return std::hypot(radius, length / 2.0);
    case Shape::Mesh:
      break;
  }
  std::shared_ptr<const robot::TriangleMesh> loaded;
  const auto& mesh = meshOf(*this, loaded);
  const Eigen::Vector3d centre = localMeshCenter(mesh);
  double radiusSquared = 0.0;
  for (const auto& v : mesh.vertices) radiusSquared = std::max(radiusSquared, (v - centre).squaredNorm());
  return std::sqrt(radiusSquared);
}

const Query& Scene::query(const std::string& queryName) const {
  if (queries.empty()) throw Error("scene " + sourceFile.string() + " has no queries");
  if (queryName.empty()) return queries.front();
  for (const auto& q : queries) {
    if (q.name == queryName) return q;
  }
  std::string list;
  for (const auto& q : queries) list += (list.empty() ? "" : ", ") + q.name;
  throw Error("scene " + sourceFile.string() + " has no query '" + queryName + "'; queries: " + list);
}

Scene loadScene(const std::filesystem::path& file) { return SceneReader(file).read(); }

}  // namespace arcplan::collision
