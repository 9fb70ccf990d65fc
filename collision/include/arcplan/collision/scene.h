#pragma once
// A planning scene as written in data/scenes/*.yaml (docs/formats.md, docs/collision.md): the robot, obstacles with
// poses, extra allowed-collision pairs, and named queries (start/goal as a tool0 pose or joints).
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "arcplan/robot/mesh.h"
#include "arcplan/robot/robot_source.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::collision {

struct Obstacle {
  enum class Shape { Sphere, Box, Cylinder, Mesh };
  std::string name;
  Shape shape = Shape::Sphere;
  double radius = 0.0;                                  // sphere, cylinder
  double length = 0.0;                                  // cylinder, along its local z, centred
  Eigen::Vector3d size = Eigen::Vector3d::Zero();       // box edge lengths
  std::filesystem::path meshFile;                       // mesh (resolved path)
  Eigen::Vector3d meshScale = Eigen::Vector3d::Ones();  // mesh
  // The mesh, scaled, in the obstacle frame; loadScene fills it (checking the file once). When it
  // is empty, users of the obstacle load meshFile themselves.
  std::shared_ptr<const robot::TriangleMesh> meshData;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // in base_link

  // A ball that contains the whole obstacle: the thesis' "circumscribed ball" (centre in base_link).
  Eigen::Vector3d boundingCenter() const;
  double boundingRadius() const;
};

// A body the robot holds (MoveIt's attached collision object, a gripped part): it moves with `link`
// (body.pose is in that link's frame) and is checked like a link against obstacles and other links.
struct AttachedObstacle {
  Obstacle body;
  std::string link;
};

// One end of a query: a tool0 pose (optionally with a seed choosing the IK branch) or joints.
struct QueryEndpoint {
  std::optional<std::array<double, 6>> pose;  // x, y, z, roll, pitch, yaw
  std::optional<robot::Vector6> seed;
  std::optional<robot::Vector6> joints;
};

struct Query {
  std::string name;
  QueryEndpoint start;
  QueryEndpoint goal;
};

struct Scene {
  std::string name;
  std::filesystem::path sourceFile;
  robot::RobotSource robot;  // nothing given: arcplan's built-in UR10e
  std::vector<Obstacle> obstacles;
  std::vector<AttachedObstacle> attachedObstacles;  // MoveIt scenes; their touch links are allowed pairs
  std::vector<std::pair<std::string, std::string>> allowedCollisions;  // link/obstacle name pairs
  std::vector<Query> queries;

  // The named query, or the first one for an empty name. Throws arcplan::Error listing the names.
  const Query& query(const std::string& name) const;
};

// Reads a scene YAML (yaml-cpp). Throws arcplan::Error with file, line and field on bad input:
// unknown keys or shapes, missing fields, wrong vector lengths, non-positive sizes, missing mesh file.
Scene loadScene(const std::filesystem::path& file);

// The scene as a scene YAML document that loadScene reads back to the same obstacles, allowed pairs
// and queries (numbers with 15 significant digits; mesh files and URDFs as resolved paths).
std::string sceneToYaml(const Scene& scene);
// sceneToYaml into `file`, atomically (a failure leaves no half-written file).
void writeScene(const Scene& scene, const std::filesystem::path& file);

}  // namespace arcplan::collision
