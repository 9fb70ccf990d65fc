#pragma once
// Internal to the MoveIt readers (moveit_scene.h): the URDF's frames as MoveIt sees them (every link
// of the tree, not only arcplan's arm chain), message fields that ROS tools write in two spellings
// (a vector as [x, y, z] or {x: .., y: .., z: ..}), and MoveIt bodies converted to obstacles.
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "arcplan/collision/moveit_scene.h"
#include "arcplan/collision/scene.h"
#include "arcplan/common/yaml_reading.h"
#include "arcplan/robot/robot_model.h"

namespace arcplan::collision::detail {

// The robot's link tree as MoveIt sees it: link poses in the root frame for given joint values (missing
// joints at 0). From a URDF (urdfdom: every link, gripper fingers and mimic joints included), or from
// a robot built without one (a UR type from UR's description: its links are the whole robot).
class UrdfFrames {
public:
  explicit UrdfFrames(const std::filesystem::path& urdf);
  explicit UrdfFrames(const robot::RobotModel& model);
  // What the names are checked against, for messages: "the URDF <file>", "UR description type ur5e".
  const std::string& description() const { return description_; }
  const std::string& root() const { return root_; }
  bool hasLink(const std::string& link) const { return parentJoint_.count(link) != 0 || link == root_; }
  bool hasJoint(const std::string& joint) const { return joints_.count(joint) != 0; }
  // Links with <collision> elements: the names a complete MoveIt allowed-collision matrix lists.
  const std::set<std::string>& collisionLinks() const { return collisionLinks_; }
  Eigen::Isometry3d linkInRoot(const std::string& link, const std::map<std::string, double>& joints) const;

private:
  struct JointInfo {
    std::string parent, child;
    Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    enum class Kind { Fixed, Revolute, Prismatic } kind = Kind::Fixed;
  };
  struct Mimic {
    std::string master;
    double multiplier = 1.0, offset = 0.0;
  };
  // A mimic joint follows its master (gripper fingers) when the master is given.
  double jointValue(const std::string& joint, const std::map<std::string, double>& joints) const;
  std::string description_;
  std::string root_;
  std::map<std::string, JointInfo> joints_;
  std::map<std::string, Mimic> mimics_;
  std::map<std::string, std::string> parentJoint_;  // child link -> joint
  std::set<std::string> collisionLinks_;
};

// The robot model (base_link -> tool0) and frames of a URDF or UR type, loaded once per process and
// description (its files' contents, file_content.h): a benchmark folder reads hundreds of scenes and
// requests against the same robot, and loading its meshes dominates reading a message. At most
// kDescriptionCacheEntries descriptions are kept, the least recently used dropped first (as the mesh
// parts, mesh_part_cache.h): a long Python session may read one description after another.
inline constexpr std::size_t kDescriptionCacheEntries = 64;
std::shared_ptr<const robot::RobotModel> sharedRobotModel(const MoveItRobot& robot);
std::shared_ptr<const UrdfFrames> sharedUrdfFrames(const MoveItRobot& robot);
// How many descriptions the cache holds now (for tests of its bound).
std::size_t descriptionCacheSize();

// A cone along its local z (tip at +height/2, base disc at -height/2), as a closed triangle mesh whose
// side polygon is circumscribed, so it contains the true cone.
robot::TriangleMesh coneMesh(double height, double radius, int segments = 32);

// Reads the fields common to PlanningScene and MotionPlanRequest messages.
class MessageReader {
public:
  explicit MessageReader(const std::filesystem::path& file) : yaml(file) {}
  YamlReader yaml;

  // The file's top-level mapping, a message of `type` (as errors name it) with only the fields `keys`.
  YAML::Node message(const std::string& what, const std::string& field, const std::string& type,
                     const std::vector<std::string>& keys) const;
  Eigen::Vector3d vector3(const YAML::Node& node, const std::string& field) const;
  // Normalised; a zero-norm or non-finite quaternion is an error.
  Eigen::Quaterniond quaternion(const YAML::Node& node, const std::string& field) const;
  // geometry_msgs/Pose {position, orientation}; an absent pose is the identity.
  Eigen::Isometry3d pose(const YAML::Node& node, const std::string& field) const;
  // shape_msgs/SolidPrimitive -> an obstacle (no name, identity pose).
  Obstacle primitive(const YAML::Node& node, const std::string& field) const;
  // shape_msgs/Mesh {vertices, triangles} -> an obstacle holding the mesh.
  Obstacle mesh(const YAML::Node& node, const std::string& field) const;
  // sensor_msgs/JointState names and positions (two lists of equal length).
  std::map<std::string, double> jointState(const YAML::Node& node, const std::string& field) const;
};

// The obstacles of one object: its name alone for one shape, "id[k]" for the k-th of several.
std::string partName(const std::string& id, std::size_t index, std::size_t count);

}  // namespace arcplan::collision::detail
