// moveit_msgs/PlanningScene YAML -> Scene (moveit_scene.h).
#include <algorithm>
#include <set>

#include "arcplan/collision/moveit_scene.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/robot/robot_model.h"
#include "moveit_reading.h"
#include "moveit_scene_building.h"

namespace arcplan::collision {
namespace {

using detail::MessageReader;

class PlanningSceneReader {
public:
  PlanningSceneReader(const std::filesystem::path& file, const MoveItRobot& robot)
      : message_(file), builder_(robot, file) {}

  MoveItProblem read() {
    const YAML::Node root = message_.message(
        "MoveIt planning scene", "planning scene", "moveit_msgs/PlanningScene",
        {"name", "robot_state", "robot_model_name", "fixed_frame_transforms", "allowed_collision_matrix",
         "link_padding", "link_scale", "object_colors", "world", "is_diff"});
    if (const auto name = root["name"]; name && name.IsScalar() && !name.Scalar().empty())
      builder_.setName(name.Scalar());
    // The robot state first: link frames and attached bodies depend on its joints.
    const YAML::Node state = root["robot_state"];
    if (state && !state.IsNull()) {
      message_.yaml.checkKeys(state, "robot_state",
                              {"joint_state", "multi_dof_joint_state", "attached_collision_objects", "is_diff"});
      builder_.setJoints(readJoints(state["joint_state"], "robot_state.joint_state"));
    }
    if (const auto transforms = root["fixed_frame_transforms"]) readFixedFrames(transforms);
    if (const auto world = root["world"]; world && !world.IsNull()) {
      message_.yaml.checkKeys(world, "world", {"collision_objects", "octomap"});
      if (const auto octomap = world["octomap"]; octomap && octomap.IsMap() && octomap["octomap"] &&
                                                 octomap["octomap"]["data"] && octomap["octomap"]["data"].size() > 0)
        message_.yaml.fail(octomap, "world.octomap", "octomaps are not supported; give the obstacles as objects");
      if (const auto objects = world["collision_objects"]; objects && !objects.IsNull()) {
        message_.yaml.expectSequence(objects, "world.collision_objects");
        for (std::size_t i = 0; i < objects.size(); ++i)
          readObject(objects[i], "world.collision_objects[" + std::to_string(i) + "]", "");
      }
    }
    if (state && state["attached_collision_objects"]) readAttached(state["attached_collision_objects"]);
    if (const auto matrix = root["allowed_collision_matrix"]; matrix && !matrix.IsNull()) readMatrix(matrix);
    return builder_.finish();
  }

private:
  std::map<std::string, double> readJoints(const YAML::Node& node, const std::string& field) const {
    auto joints = message_.jointState(node, field);
    for (const auto& [name, value] : joints) {
      if (!builder_.frames().hasJoint(name))
        message_.yaml.fail(node, field, "joint '" + name + "' is no joint of " + builder_.frames().description());
    }
    return joints;
  }

  void readFixedFrames(const YAML::Node& transforms) {
    message_.yaml.expectSequence(transforms, "fixed_frame_transforms");
    for (std::size_t i = 0; i < transforms.size(); ++i) {
      const std::string field = "fixed_frame_transforms[" + std::to_string(i) + "]";
      const YAML::Node node = transforms[i];
      message_.yaml.checkKeys(node, field, {"header", "child_frame_id", "transform"});
      const std::string child =
          message_.yaml.text(message_.yaml.required(node, "child_frame_id", field), field + ".child_frame_id");
      const YAML::Node transform = message_.yaml.required(node, "transform", field);
      message_.yaml.checkKeys(transform, field + ".transform", {"translation", "rotation"});
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      if (transform["translation"])
        pose.translation() = message_.vector3(transform["translation"], field + ".transform.translation");
      if (transform["rotation"])
        pose.linear() = message_.quaternion(transform["rotation"], field + ".transform.rotation").matrix();
      builder_.addFixedFrame(child, frameOf(node["header"], field + ".header") * pose);
    }
  }

  // The header's frame in the planning frame.
  Eigen::Isometry3d frameOf(const YAML::Node& header, const std::string& field) const {
    if (!header || header.IsNull()) return Eigen::Isometry3d::Identity();
    message_.yaml.checkKeys(header, field, {"seq", "stamp", "frame_id"});
    const YAML::Node frame = header["frame_id"];
    if (!frame || frame.IsNull()) return Eigen::Isometry3d::Identity();
    if (!frame.IsScalar()) message_.yaml.fail(frame, field + ".frame_id", "expected a frame name");
    const auto pose = builder_.frameInPlanningFrame(frame.Scalar());
    if (!pose) {
      message_.yaml.fail(frame, field + ".frame_id",
                         "unknown frame '" + frame.Scalar() + "': expected the planning frame '" +
                             builder_.frames().root() + "', 'world', a fixed frame or a link of the robot");
    }
    return *pose;
  }

  // One CollisionObject: its shapes as obstacles (in the planning frame), kept under `attachedTo`'s
  // link when that is not empty.
  void readObject(const YAML::Node& node, const std::string& field, const std::string& attachedTo,
                  const std::vector<std::string>& touchLinks = {}) {
    message_.yaml.checkKeys(node, field,
                            {"header", "pose", "id", "type", "primitives", "primitive_poses", "meshes", "mesh_poses",
                             "planes", "plane_poses", "subframe_names", "subframe_poses", "operation"});
    const std::string id = message_.yaml.text(message_.yaml.required(node, "id", field), field + ".id");
    checkOperation(node["operation"], field + ".operation");
    if (const auto planes = node["planes"]; planes && planes.IsSequence() && planes.size() > 0)
      message_.yaml.fail(planes, field + ".planes", "infinite planes are not supported; use a thin box");
    const Eigen::Isometry3d objectPose =
        frameOf(node["header"], field + ".header") * message_.pose(node["pose"], field + ".pose");
    std::vector<Obstacle> shapes;
    readShapes(node, field, "primitives", "primitive_poses", objectPose, shapes);
    readShapes(node, field, "meshes", "mesh_poses", objectPose, shapes);
    if (shapes.empty()) message_.yaml.fail(node, field, "object '" + id + "' has no primitives or meshes");
    if (!builder_.addObject(id, std::move(shapes), attachedTo, touchLinks))
      message_.yaml.fail(node["id"], field + ".id", builder_.problem());
  }

  void checkOperation(const YAML::Node& node, const std::string& field) const {
    if (!node || node.IsNull()) return;
    const std::string value = node.IsScalar() ? node.Scalar() : std::string();
    // ADD (0) and APPEND (2) both add the shapes to a scene that starts empty.
    if (value != "0" && value != "2" && value != "add" && value != "ADD" && value != "append" && value != "APPEND")
      message_.yaml.fail(node, field, "expected ADD (0) or APPEND (2); a scene file is read as a whole, not as a diff");
  }

  void readShapes(const YAML::Node& object, const std::string& field, const char* shapesKey, const char* posesKey,
                  const Eigen::Isometry3d& objectPose, std::vector<Obstacle>& shapes) const {
    const YAML::Node list = object[shapesKey];
    if (!list || list.IsNull()) return;
    message_.yaml.expectSequence(list, field + "." + shapesKey);
    const YAML::Node poses = object[posesKey];
    const std::size_t poseCount = poses && poses.IsSequence() ? poses.size() : 0;
    if (poseCount != list.size()) {
      message_.yaml.fail(poses ? poses : object, field + "." + posesKey,
                         "expected one pose per entry of " + std::string(shapesKey) + " (" +
                             std::to_string(list.size()) + "), got " + std::to_string(poseCount));
    }
    const bool primitives = std::string(shapesKey) == "primitives";
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string where = field + "." + shapesKey + "[" + std::to_string(i) + "]";
      message_.yaml.expectMap(list[i], where);
      Obstacle shape = primitives ? message_.primitive(list[i], where) : message_.mesh(list[i], where);
      shape.pose = objectPose * message_.pose(poses[i], field + "." + posesKey + "[" + std::to_string(i) + "]");
      shapes.push_back(std::move(shape));
    }
  }

  void readAttached(const YAML::Node& list) {
    if (list.IsNull()) return;
    message_.yaml.expectSequence(list, "robot_state.attached_collision_objects");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string field = "robot_state.attached_collision_objects[" + std::to_string(i) + "]";
      const YAML::Node node = list[i];
      message_.yaml.checkKeys(node, field, {"link_name", "object", "touch_links", "detach_posture", "weight"});
      const YAML::Node linkNode = message_.yaml.required(node, "link_name", field);
      const std::string link = message_.yaml.text(linkNode, field + ".link_name");
      if (!builder_.frames().hasLink(link))
        message_.yaml.fail(linkNode, field + ".link_name", "no link '" + link + "'");
      std::vector<std::string> touch;
      if (const auto links = node["touch_links"]; links && !links.IsNull()) {
        message_.yaml.expectSequence(links, field + ".touch_links");
        for (std::size_t k = 0; k < links.size(); ++k) {
          touch.push_back(message_.yaml.text(links[k], field + ".touch_links[" + std::to_string(k) + "]"));
          if (!builder_.frames().hasLink(touch.back()))
            message_.yaml.fail(links[k], field + ".touch_links", "no link '" + touch.back() + "'");
        }
      }
      // An object without a frame is given in its link's frame (MoveIt's rule for attached bodies).
      YAML::Node object = message_.yaml.required(node, "object", field);
      if (!object.IsMap()) message_.yaml.fail(object, field + ".object", "expected a CollisionObject");
      YAML::Node copy = YAML::Clone(object);
      if (!copy["header"] || !copy["header"]["frame_id"] || copy["header"]["frame_id"].Scalar().empty())
        copy["header"]["frame_id"] = link;
      readObject(copy, field + ".object", link, touch);
    }
  }

  void readMatrix(const YAML::Node& matrix) {
    message_.yaml.checkKeys(matrix, "allowed_collision_matrix",
                            {"entry_names", "entry_values", "default_entry_names", "default_entry_values"});
    const auto names = textList(matrix["entry_names"], "allowed_collision_matrix.entry_names");
    const YAML::Node rows = matrix["entry_values"];
    const std::size_t rowCount = rows && rows.IsSequence() ? rows.size() : 0;
    if (rowCount != names.size()) {
      message_.yaml.fail(
          rows ? rows : matrix, "allowed_collision_matrix.entry_values",
          "expected " + std::to_string(names.size()) + " rows (one per entry name), got " + std::to_string(rowCount));
    }
    std::vector<std::size_t> unknown;
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (!builder_.isKnownName(names[i])) unknown.push_back(i);
    }
    // A complete matrix (every link with collision geometry named) is what MoveIt exports; an extra
    // name there is a link of the description it came from (MotionBenchMaker's "box_link") and does
    // not change which pairs of this robot are allowed. In a hand-written matrix it is a typo.
    const bool complete = std::all_of(
        builder_.frames().collisionLinks().begin(), builder_.frames().collisionLinks().end(),
        [&](const std::string& link) { return std::find(names.begin(), names.end(), link) != names.end(); });
    if (!unknown.empty() && !complete) {
      std::string list, missing;
      for (const std::size_t i : unknown) list += (list.empty() ? "'" : ", '") + names[i] + "'";
      for (const auto& link : builder_.frames().collisionLinks()) {
        if (std::find(names.begin(), names.end(), link) == names.end()) missing += (missing.empty() ? "" : ", ") + link;
      }
      message_.yaml.fail(matrix["entry_names"][unknown.front()],
                         "allowed_collision_matrix.entry_names[" + std::to_string(unknown.front()) + "]",
                         list + (unknown.size() == 1 ? " is" : " are") +
                             " no link of the robot and no collision object (links not named: " + missing + ")");
    }
    for (const std::size_t i : unknown) builder_.ignoreMatrixName(names[i]);
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string field = "allowed_collision_matrix.entry_values[" + std::to_string(i) + "]";
      YAML::Node row = rows[i];
      if (row.IsMap()) {  // moveit_msgs/AllowedCollisionEntry as ROS tools write it: {enabled: [...]}
        message_.yaml.checkKeys(row, field, {"enabled"});
        row = message_.yaml.required(row, "enabled", field);
      }
      const auto values = booleans(row, field, names.size());
      for (std::size_t j = 0; j < names.size(); ++j) {
        if (values[j]) builder_.allow(names[i], names[j]);
      }
    }
    readDefaultEntries(matrix);
  }

  void readDefaultEntries(const YAML::Node& matrix) {
    const auto names = textList(matrix["default_entry_names"], "allowed_collision_matrix.default_entry_names");
    const auto values =
        booleans(matrix["default_entry_values"], "allowed_collision_matrix.default_entry_values", names.size(), matrix);
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (!builder_.isKnownName(names[i])) {
        message_.yaml.fail(matrix["default_entry_names"][i], "allowed_collision_matrix.default_entry_names",
                           "'" + names[i] + "' is no link of the robot and no collision object");
      }
      if (values[i]) builder_.allowWithEverything(names[i]);
    }
  }

  std::vector<std::string> textList(const YAML::Node& node, const std::string& field) const {
    std::vector<std::string> values;
    if (!node || node.IsNull()) return values;
    message_.yaml.expectSequence(node, field);
    for (std::size_t i = 0; i < node.size(); ++i)
      values.push_back(message_.yaml.text(node[i], field + "[" + std::to_string(i) + "]"));
    return values;
  }

  // `parent` holds the list: an absent list (which has no position) is reported where its parent is.
  std::vector<bool> booleans(const YAML::Node& node, const std::string& field, std::size_t count,
                             const YAML::Node& parent = {}) const {
    if (count == 0 && (!node || node.IsNull())) return {};
    if (!node || !node.IsSequence() || node.size() != count)
      message_.yaml.fail(node ? node : parent, field,
                         "expected a list of " + std::to_string(count) + " true/false values");
    std::vector<bool> values;
    for (std::size_t i = 0; i < count; ++i) {
      bool value = false;
      if (!node[i].IsScalar() || !YAML::convert<bool>::decode(node[i], value)) {
        message_.yaml.fail(node[i], field + "[" + std::to_string(i) + "]", "expected true or false");
      }
      values.push_back(value);
    }
    return values;
  }

  MessageReader message_;
  detail::SceneBuilder builder_;
};

}  // namespace

MoveItProblem loadMoveItScene(const std::filesystem::path& sceneFile, const MoveItRobot& robot) {
  return PlanningSceneReader(sceneFile, robot).read();
}

}  // namespace arcplan::collision
