#include "moveit_reading.h"

#include <cmath>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "arcplan/common/error.h"
#include "arcplan/robot/ur_description.h"
#include "file_content.h"
#include "lru_cache.h"

namespace arcplan::collision::detail {
namespace {

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  result.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z).normalized().matrix();
  return result;
}

// SolidPrimitive's type as MoveIt writes it: the constant's name (any case) or its number.
enum class PrimitiveType { Box = 1, Sphere = 2, Cylinder = 3, Cone = 4 };

}  // namespace

UrdfFrames::UrdfFrames(const std::filesystem::path& urdf) {
  std::ifstream in(urdf);
  std::stringstream text;
  text << in.rdbuf();
  // urdfdom's warnings (undefined materials) were already shown, or suppressed, by the robot loader.
  console_bridge::noOutputHandler();
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(text.str());
  console_bridge::restorePreviousOutputHandler();
  if (!model || !model->getRoot()) throw Error(urdf.string() + ": not a URDF robot description");
  description_ = "the URDF " + urdf.string();
  root_ = model->getRoot()->name;
  for (const auto& [name, joint] : model->joints_) {
    JointInfo info;
    info.parent = joint->parent_link_name;
    info.child = joint->child_link_name;
    info.origin = toIsometry(joint->parent_to_joint_origin_transform);
    info.axis = Eigen::Vector3d(joint->axis.x, joint->axis.y, joint->axis.z);
    if (info.axis.norm() > 0.0) info.axis.normalize();
    switch (joint->type) {
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
        info.kind = JointInfo::Kind::Revolute;
        break;
      case urdf::Joint::PRISMATIC:
        info.kind = JointInfo::Kind::Prismatic;
        break;
      default:
        info.kind = JointInfo::Kind::Fixed;  // floating and planar joints: at their origin
        break;
    }
    if (joint->mimic) mimics_[name] = {joint->mimic->joint_name, joint->mimic->multiplier, joint->mimic->offset};
    parentJoint_[info.child] = name;
    joints_[name] = info;
  }
  for (const auto& [name, link] : model->links_) {
    if (link->collision || !link->collision_array.empty()) collisionLinks_.insert(name);
  }
}

UrdfFrames::UrdfFrames(const robot::RobotModel& model) : description_("the robot '" + model.name() + "'") {
  const auto& links = model.links();
  root_ = links[model.baseLink()].name;
  for (const robot::Link& link : links) {
    if (!link.collisions.empty()) collisionLinks_.insert(link.name);
    if (link.parent < 0) continue;
    JointInfo info;
    info.parent = links[link.parent].name;
    info.child = link.name;
    info.origin = link.originInParent;
    info.axis = link.axis;
    info.kind = link.joint >= 0 ? JointInfo::Kind::Revolute : JointInfo::Kind::Fixed;
    // A fixed joint has no name in the model; this one cannot be a ROS name, so no message matches it.
    const std::string name = link.joint >= 0 ? model.joints()[link.joint].name : "(fixed) " + link.name;
    parentJoint_[info.child] = name;
    joints_[name] = info;
  }
}

namespace {

// What a description is, as a cache key: its files' contents (file_content.h), so a file changed on disk
// is read again.
std::string descriptionKey(const MoveItRobot& robot) {
  const auto content = [](const std::filesystem::path& file) {
    const auto [hash, size] = fileContentKey(file);
    return std::filesystem::absolute(file).string() + "#" + std::to_string(hash) + ":" + std::to_string(size);
  };
  if (!robot.urdf.empty() || robot.urDescription.type.empty()) return "urdf\n" + content(robot.urdf);
  const auto& ur = robot.urDescription;
  const auto folder = ur.folder.empty() ? robot::defaultUrDescriptionFolder() : ur.folder;
  const auto config = folder / "config" / ur.type;
  // Every file of the type's folder (kinematics, limits, masses, meshes named), and a calibration file.
  std::set<std::filesystem::path> files;
  std::error_code missing;  // a missing folder: loadUrDescription says so
  for (const auto& entry : std::filesystem::directory_iterator(config, missing))
    if (entry.is_regular_file()) files.insert(entry.path());
  if (!ur.kinematics.empty()) files.insert(ur.kinematics);
  std::string key = "ur\n" + ur.type + "\n" + std::filesystem::absolute(config).string();
  for (const auto& file : files) key += "\n" + content(file);
  return key;
}

robot::RobotModel loadModel(const MoveItRobot& robot) {
  if (!robot.urdf.empty() || robot.urDescription.type.empty()) return robot::loadRobotModel(robot.urdf);
  return robot::loadUrDescription(robot.urDescription);
}

// A description's model and frames, each read when first asked for.
struct Description {
  std::shared_ptr<const robot::RobotModel> model;
  std::shared_ptr<const UrdfFrames> frames;
};

struct DescriptionCache {
  std::mutex mutex;
  LruCache<std::string, Description> descriptions{kDescriptionCacheEntries};
};

DescriptionCache& descriptionCache() {
  static DescriptionCache instance;
  return instance;
}

// The cache entry of `robot`'s description; the caller holds the cache's mutex.
Description& descriptionOf(DescriptionCache& cache, const MoveItRobot& robot) {
  const std::string key = descriptionKey(robot);
  if (Description* found = cache.descriptions.find(key)) return *found;
  return cache.descriptions.insert(key, {});
}

std::shared_ptr<const robot::RobotModel> modelOf(Description& description, const MoveItRobot& robot) {
  if (!description.model) description.model = std::make_shared<const robot::RobotModel>(loadModel(robot));
  return description.model;
}

}  // namespace

std::shared_ptr<const robot::RobotModel> sharedRobotModel(const MoveItRobot& robot) {
  DescriptionCache& cache = descriptionCache();
  const std::lock_guard<std::mutex> lock(cache.mutex);
  return modelOf(descriptionOf(cache, robot), robot);
}

std::shared_ptr<const UrdfFrames> sharedUrdfFrames(const MoveItRobot& robot) {
  DescriptionCache& cache = descriptionCache();
  const std::lock_guard<std::mutex> lock(cache.mutex);
  Description& description = descriptionOf(cache, robot);
  if (!description.frames) {
    description.frames = !robot.urdf.empty() || robot.urDescription.type.empty()
                             ? std::make_shared<const UrdfFrames>(robot.urdf)
                             : std::make_shared<const UrdfFrames>(*modelOf(description, robot));
  }
  return description.frames;
}

std::size_t descriptionCacheSize() {
  DescriptionCache& cache = descriptionCache();
  const std::lock_guard<std::mutex> lock(cache.mutex);
  return cache.descriptions.size();
}

double UrdfFrames::jointValue(const std::string& joint, const std::map<std::string, double>& joints) const {
  if (const auto mimic = mimics_.find(joint); mimic != mimics_.end()) {
    const auto master = joints.find(mimic->second.master);
    if (master != joints.end()) return mimic->second.multiplier * master->second + mimic->second.offset;
  }
  const auto given = joints.find(joint);
  return given == joints.end() ? 0.0 : given->second;
}

Eigen::Isometry3d UrdfFrames::linkInRoot(const std::string& link, const std::map<std::string, double>& joints) const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::string current = link;
  for (auto found = parentJoint_.find(current); found != parentJoint_.end(); found = parentJoint_.find(current)) {
    const JointInfo& joint = joints_.at(found->second);
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    const double q = jointValue(found->second, joints);
    if (joint.kind == JointInfo::Kind::Revolute) motion.linear() = Eigen::AngleAxisd(q, joint.axis).matrix();
    if (joint.kind == JointInfo::Kind::Prismatic) motion.translation() = q * joint.axis;
    pose = joint.origin * motion * pose;
    current = joint.parent;
  }
  return pose;
}

robot::TriangleMesh coneMesh(double height, double radius, int segments) {
  robot::TriangleMesh mesh;
  const double outer = radius / std::cos(M_PI / segments);  // circumscribed polygon
  mesh.vertices.emplace_back(0.0, 0.0, height / 2.0);       // tip
  mesh.vertices.emplace_back(0.0, 0.0, -height / 2.0);      // base centre
  for (int k = 0; k < segments; ++k) {
    const double angle = 2.0 * M_PI * k / segments;
    mesh.vertices.emplace_back(outer * std::cos(angle), outer * std::sin(angle), -height / 2.0);
  }
  for (int k = 0; k < segments; ++k) {
    const int a = 2 + k, b = 2 + (k + 1) % segments;
    mesh.triangles.emplace_back(0, a, b);  // side, counter-clockwise seen from outside
    mesh.triangles.emplace_back(1, b, a);  // base, facing -z
  }
  return mesh;
}

YAML::Node MessageReader::message(const std::string& what, const std::string& field, const std::string& type,
                                  const std::vector<std::string>& keys) const {
  const YAML::Node root = yaml.load(what);
  if (!root.IsMap()) yaml.fail(root, field, "expected a " + type + " mapping");
  yaml.checkKeys(root, field, keys);
  return root;
}

Eigen::Vector3d MessageReader::vector3(const YAML::Node& node, const std::string& field) const {
  if (node.IsMap()) {
    yaml.checkKeys(node, field, {"x", "y", "z"});
    return {yaml.number(yaml.required(node, "x", field), field + ".x"),
            yaml.number(yaml.required(node, "y", field), field + ".y"),
            yaml.number(yaml.required(node, "z", field), field + ".z")};
  }
  const auto values = yaml.numbers(node, field, 3);
  return {values[0], values[1], values[2]};
}

Eigen::Quaterniond MessageReader::quaternion(const YAML::Node& node, const std::string& field) const {
  Eigen::Vector4d xyzw;
  if (node.IsMap()) {
    yaml.checkKeys(node, field, {"x", "y", "z", "w"});
    int k = 0;
    for (const char* key : {"x", "y", "z", "w"})
      xyzw[k++] = yaml.number(yaml.required(node, key, field), field + "." + key);
  } else {
    const auto values = yaml.numbers(node, field, 4);
    xyzw = Eigen::Vector4d(values[0], values[1], values[2], values[3]);
  }
  // A zero quaternion is no rotation at all (MoveIt refuses it too); anything else is normalised,
  // since files rounded to a few digits are slightly off unit length.
  if (!(xyzw.norm() > 1e-9)) yaml.fail(node, field, "quaternion [x, y, z, w] of zero norm is no rotation");
  xyzw.normalize();
  return Eigen::Quaterniond(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);
}

Eigen::Isometry3d MessageReader::pose(const YAML::Node& node, const std::string& field) const {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  if (!node || node.IsNull()) return result;
  yaml.checkKeys(node, field, {"position", "orientation"});
  if (const auto position = node["position"]) result.translation() = vector3(position, field + ".position");
  if (const auto orientation = node["orientation"])
    result.linear() = quaternion(orientation, field + ".orientation").matrix();
  return result;
}

Obstacle MessageReader::primitive(const YAML::Node& node, const std::string& field) const {
  yaml.checkKeys(node, field, {"type", "dimensions", "polygon"});
  const YAML::Node typeNode = yaml.required(node, "type", field);
  std::string type = yaml.text(typeNode, field + ".type");
  for (auto& c : type) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::map<std::string, PrimitiveType> types = {
      {"box", PrimitiveType::Box},           {"1", PrimitiveType::Box},
      {"sphere", PrimitiveType::Sphere},     {"2", PrimitiveType::Sphere},
      {"cylinder", PrimitiveType::Cylinder}, {"3", PrimitiveType::Cylinder},
      {"cone", PrimitiveType::Cone},         {"4", PrimitiveType::Cone}};
  const auto found = types.find(type);
  if (found == types.end()) {
    yaml.fail(
        typeNode, field + ".type",
        "unknown primitive type '" + typeNode.Scalar() + "'; expected box (1), sphere (2), cylinder (3) or cone (4)");
  }
  const YAML::Node dimensions = yaml.required(node, "dimensions", field);
  Obstacle obstacle;
  switch (found->second) {
    case PrimitiveType::Box: {
      const auto size = yaml.positives(dimensions, field + ".dimensions [x, y, z]", 3);
      obstacle.shape = Obstacle::Shape::Box;
      obstacle.size = Eigen::Vector3d(size[0], size[1], size[2]);
      break;
    }
    case PrimitiveType::Sphere:
      obstacle.shape = Obstacle::Shape::Sphere;
      obstacle.radius = yaml.positives(dimensions, field + ".dimensions [radius]", 1)[0];
      break;
    case PrimitiveType::Cylinder: {
      const auto values = yaml.positives(dimensions, field + ".dimensions [height, radius]", 2);
      obstacle.shape = Obstacle::Shape::Cylinder;
      obstacle.length = values[0];
      obstacle.radius = values[1];
      break;
    }
    case PrimitiveType::Cone: {
      const auto values = yaml.positives(dimensions, field + ".dimensions [height, radius]", 2);
      obstacle.shape = Obstacle::Shape::Mesh;
      obstacle.meshData = std::make_shared<const robot::TriangleMesh>(coneMesh(values[0], values[1]));
      break;
    }
  }
  return obstacle;
}

Obstacle MessageReader::mesh(const YAML::Node& node, const std::string& field) const {
  yaml.checkKeys(node, field, {"vertices", "triangles"});
  const YAML::Node vertices = yaml.required(node, "vertices", field);
  const YAML::Node triangles = yaml.required(node, "triangles", field);
  yaml.expectSequence(vertices, field + ".vertices");
  yaml.expectSequence(triangles, field + ".triangles");
  if (triangles.size() == 0) yaml.fail(triangles, field + ".triangles", "a mesh needs at least one triangle");
  robot::TriangleMesh mesh;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    mesh.vertices.push_back(vector3(vertices[i], field + ".vertices[" + std::to_string(i) + "]"));
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const std::string where = field + ".triangles[" + std::to_string(i) + "]";
    YAML::Node indices = triangles[i];
    if (indices.IsMap()) {
      yaml.checkKeys(indices, where, {"vertex_indices"});
      indices = yaml.required(indices, "vertex_indices", where);
    }
    Eigen::Vector3i triangle;
    for (int k = 0; k < 3; ++k) {
      if (!indices.IsSequence() || indices.size() != 3) yaml.fail(indices, where, "expected 3 vertex indices");
      triangle[k] =
          static_cast<int>(yaml.wholeNumber(indices[k], where, 0, static_cast<long long>(vertices.size()) - 1));
    }
    mesh.triangles.push_back(triangle);
  }
  Obstacle obstacle;
  obstacle.shape = Obstacle::Shape::Mesh;
  obstacle.meshData = std::make_shared<const robot::TriangleMesh>(std::move(mesh));
  return obstacle;
}

std::map<std::string, double> MessageReader::jointState(const YAML::Node& node, const std::string& field) const {
  std::map<std::string, double> joints;
  if (!node || node.IsNull()) return joints;
  yaml.checkKeys(node, field, {"header", "name", "position", "velocity", "effort"});
  const YAML::Node names = node["name"], positions = node["position"];
  if (!names && !positions) return joints;
  if (!names || !positions) yaml.fail(node, field, "expected both 'name' and 'position'");
  yaml.expectSequence(names, field + ".name");
  yaml.expectSequence(positions, field + ".position");
  if (names.size() != positions.size()) {
    yaml.fail(positions, field + ".position",
              std::to_string(positions.size()) + " positions for " + std::to_string(names.size()) + " names");
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string name = yaml.text(names[i], field + ".name[" + std::to_string(i) + "]");
    if (!joints.emplace(name, yaml.number(positions[i], field + ".position[" + std::to_string(i) + "]")).second)
      yaml.fail(names[i], field + ".name", "joint '" + name + "' given twice");
  }
  return joints;
}

std::string partName(const std::string& id, std::size_t index, std::size_t count) {
  return count == 1 ? id : id + "[" + std::to_string(index) + "]";
}

}  // namespace arcplan::collision::detail
