// The scene format's writer, next to its reader (scene.cpp): what it writes, loadScene reads back
// to the same Scene (tests/collision/test_scene.cpp checks the round trip).
#include <yaml-cpp/yaml.h>

#include "arcplan/collision/scene.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/robot/pose.h"

namespace arcplan::collision {
namespace {

void emitVector(YAML::Emitter& out, const double* values, int count) {
  out << YAML::Flow << YAML::BeginSeq;
  for (int i = 0; i < count; ++i) out << values[i] + 0.0;  // + 0.0 writes -0 as 0
  out << YAML::EndSeq;
}

void emitShape(YAML::Emitter& out, const Obstacle& obstacle) {
  switch (obstacle.shape) {
    case Obstacle::Shape::Sphere:
      out << YAML::Key << "sphere" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "radius"
          << YAML::Value << obstacle.radius << YAML::EndMap;
      break;
    case Obstacle::Shape::Box:
      out << YAML::Key << "box" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "size" << YAML::Value;
      emitVector(out, obstacle.size.data(), 3);
      out << YAML::EndMap;
      break;
    case Obstacle::Shape::Cylinder:
      out << YAML::Key << "cylinder" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "radius"
          << YAML::Value << obstacle.radius << YAML::Key << "length" << YAML::Value << obstacle.length << YAML::EndMap;
      break;
    case Obstacle::Shape::Mesh:
      out << YAML::Key << "mesh" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "file" << YAML::Value
          << obstacle.meshFile.string() << YAML::Key << "scale" << YAML::Value;
      emitVector(out, obstacle.meshScale.data(), 3);
      out << YAML::EndMap;
      break;
  }
}

void emitObstacle(YAML::Emitter& out, const Obstacle& obstacle) {
  out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << obstacle.name;
  emitShape(out, obstacle);
  const Eigen::Vector3d position = obstacle.pose.translation();
  const Eigen::Vector3d rpy = robot::rpyFromRotation(obstacle.pose.linear());
  out << YAML::Key << "position" << YAML::Value;
  emitVector(out, position.data(), 3);
  out << YAML::Key << "rpy" << YAML::Value;
  emitVector(out, rpy.data(), 3);
  out << YAML::EndMap;
}

void emitEndpoint(YAML::Emitter& out, const char* key, const QueryEndpoint& endpoint) {
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  if (endpoint.joints) {
    out << YAML::Key << "joints" << YAML::Value;
    emitVector(out, endpoint.joints->data(), 6);
  } else if (endpoint.pose) {
    out << YAML::Key << "pose" << YAML::Value;
    emitVector(out, endpoint.pose->data(), 6);
    if (endpoint.seed) {
      out << YAML::Key << "seed" << YAML::Value;
      emitVector(out, endpoint.seed->data(), 6);
    }
  }
  out << YAML::EndMap;
}

// `ur10e`, or the mapping the scene reader takes: urdf or ur_type (+ description, kinematics), srdf, tcp.
void emitRobot(YAML::Emitter& out, const robot::RobotSource& source) {
  const robot::ChainSelection defaultChain;
  const bool defaultTcp = source.chain.tipLink == defaultChain.tipLink && !source.chain.tcpOffset;
  if (source.isBuiltIn() && source.srdf.empty() && defaultTcp) {
    out << "ur10e";
    return;
  }
  out << YAML::BeginMap;
  const auto path = [&](const char* key, const std::filesystem::path& value) {
    if (!value.empty()) out << YAML::Key << key << YAML::Value << value.string();
  };
  path("urdf", source.isBuiltIn() ? robot::ur10eUrdfPath() : source.urdf);
  if (!source.urType.empty()) out << YAML::Key << "ur_type" << YAML::Value << source.urType;
  path("description", source.description);
  path("kinematics", source.kinematics);
  path("srdf", source.srdf);
  if (!defaultTcp) {
    out << YAML::Key << "tcp" << YAML::Value << YAML::BeginMap << YAML::Key << "link" << YAML::Value
        << source.chain.tipLink;
    if (source.chain.tcpOffset) {
      out << YAML::Key << "offset" << YAML::Value;
      emitVector(out, robot::xyzRpyFromPose(*source.chain.tcpOffset).data(), 6);
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

}  // namespace

std::string sceneToYaml(const Scene& scene) {
  YAML::Emitter out;
  out.SetDoublePrecision(15);  // readable (0.05, not 0.050000000000000003) and within 1e-15 of the value
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << scene.name;
  out << YAML::Key << "robot" << YAML::Value;
  emitRobot(out, scene.robot);
  out << YAML::Key << "obstacles" << YAML::Value << YAML::BeginSeq;
  for (const auto& obstacle : scene.obstacles) emitObstacle(out, obstacle);
  out << YAML::EndSeq;
  if (!scene.allowedCollisions.empty()) {
    out << YAML::Key << "allowed_collisions" << YAML::Value << YAML::BeginSeq;
    for (const auto& [first, second] : scene.allowedCollisions) {
      out << YAML::Flow << YAML::BeginSeq << first << second << YAML::EndSeq;
    }
    out << YAML::EndSeq;
  }
  out << YAML::Key << "queries" << YAML::Value << YAML::BeginSeq;
  for (const auto& query : scene.queries) {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << query.name;
    emitEndpoint(out, "start", query.start);
    emitEndpoint(out, "goal", query.goal);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void writeScene(const Scene& scene, const std::filesystem::path& file) {
  writeFileAtomically(file, sceneToYaml(scene));
}

}  // namespace arcplan::collision
