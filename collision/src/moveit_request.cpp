// moveit_msgs/MotionPlanRequest YAML -> the scene's query (moveit_scene.h).
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/common/error.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/robot_model.h"
#include "moveit_reading.h"

namespace arcplan::collision {
namespace {

using detail::MessageReader;

class RequestReader {
public:
  RequestReader(const std::filesystem::path& file, const robot::RobotModel& model, const detail::UrdfFrames& frames,
                MoveItProblem& problem)
      : message_(file), model_(model), frames_(frames), problem_(problem) {}

  void read() {
    const YAML::Node root = message_.message(
        "MoveIt motion plan request", "request", "moveit_msgs/MotionPlanRequest",
        {"workspace_parameters", "start_state", "goal_constraints", "path_constraints", "trajectory_constraints",
         "reference_trajectories", "pipeline_id", "planner_id", "group_name", "num_planning_attempts",
         "allowed_planning_time", "max_velocity_scaling_factor", "max_acceleration_scaling_factor",
         "cartesian_speed_end_effector_link", "max_cartesian_speed"});
    Query query;
    query.name = message_.yaml.file().stem().string();
    query.start.joints = startJoints(root["start_state"]);
    const YAML::Node goals = message_.yaml.required(root, "goal_constraints", "request");
    message_.yaml.expectSequence(goals, "goal_constraints");
    if (goals.size() == 0) message_.yaml.fail(goals, "goal_constraints", "expected at least one goal");
    // MoveIt accepts a goal satisfying any entry; arcplan plans to one, the first.
    query.goal = goal(goals[0], "goal_constraints[0]", *query.start.joints);
    problem_.scene.queries = {query};
  }

private:
  // The arm's joints: the request's start state over the scene's robot state.
  robot::Vector6 startJoints(const YAML::Node& state) {
    std::map<std::string, double>& joints = problem_.startState;
    YAML::Node where = state;
    if (state && !state.IsNull()) {
      message_.yaml.checkKeys(state, "start_state",
                              {"joint_state", "multi_dof_joint_state", "attached_collision_objects", "is_diff"});
      if (const auto attached = state["attached_collision_objects"]; attached && attached.size() > 0)
        message_.yaml.fail(attached, "start_state.attached_collision_objects",
                           "attach bodies in the planning scene's robot_state, not in the request");
      for (const auto& [name, value] : message_.jointState(state["joint_state"], "start_state.joint_state")) {
        if (!frames_.hasJoint(name))
          message_.yaml.fail(state["joint_state"], "start_state.joint_state",
                             "joint '" + name + "' is no joint of " + frames_.description());
        joints[name] = value;
      }
      if (state["joint_state"]) where = state["joint_state"];
    }
    robot::Vector6 q;
    for (int j = 0; j < 6; ++j) {
      const std::string& name = model_.joints()[j].name;
      const auto found = joints.find(name);
      if (found == joints.end()) {
        message_.yaml.fail(where ? where : YAML::Node(), "start_state",
                           "joint '" + name + "' is missing from the start state (and the scene's robot_state)");
      }
      q[j] = found->second;
    }
    return q;
  }

  QueryEndpoint goal(const YAML::Node& node, const std::string& field, const robot::Vector6& start) {
    message_.yaml.checkKeys(
        node, field,
        {"name", "joint_constraints", "position_constraints", "orientation_constraints", "visibility_constraints"});
    const YAML::Node joints = node["joint_constraints"];
    const bool hasJoints = joints && joints.IsSequence() && joints.size() > 0;
    const YAML::Node positions = node["position_constraints"];
    const bool hasPose = positions && positions.IsSequence() && positions.size() > 0;
    if (hasJoints == hasPose)
      message_.yaml.fail(node, field, "expected joint_constraints or a position + orientation constraint (not both)");
    QueryEndpoint endpoint;
    if (hasJoints) {
      endpoint.joints = jointGoal(joints, field + ".joint_constraints");
    } else {
      endpoint.pose = poseGoal(node, field);
      endpoint.seed = start;
    }
    return endpoint;
  }

  robot::Vector6 jointGoal(const YAML::Node& list, const std::string& field) const {
    std::map<std::string, double> values;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string where = field + "[" + std::to_string(i) + "]";
      message_.yaml.checkKeys(list[i], where,
                              {"joint_name", "position", "tolerance_above", "tolerance_below", "weight"});
      const YAML::Node nameNode = message_.yaml.required(list[i], "joint_name", where);
      const std::string name = message_.yaml.text(nameNode, where + ".joint_name");
      if (!frames_.hasJoint(name))
        message_.yaml.fail(nameNode, where + ".joint_name", "no joint '" + name + "' in " + frames_.description());
      values[name] = message_.yaml.number(message_.yaml.required(list[i], "position", where), where + ".position");
    }
    robot::Vector6 q;
    for (int j = 0; j < 6; ++j) {
      const auto found = values.find(model_.joints()[j].name);
      if (found == values.end())
        message_.yaml.fail(list, field, "no constraint for arm joint '" + model_.joints()[j].name + "'");
      q[j] = found->second;
    }
    return q;
  }

  // The link's target pose -> the tip's (tool0) pose in base_link, as x y z roll pitch yaw.
  std::array<double, 6> poseGoal(const YAML::Node& node, const std::string& field) const {
    const YAML::Node position = node["position_constraints"][0];
    const std::string where = field + ".position_constraints[0]";
    message_.yaml.checkKeys(position, where,
                            {"header", "link_name", "target_point_offset", "constraint_region", "weight"});
    const YAML::Node linkNode = message_.yaml.required(position, "link_name", where);
    const std::string link = message_.yaml.text(linkNode, where + ".link_name");
    const Eigen::Isometry3d linkToTip = rigidTransformToTip(link, linkNode, where + ".link_name");
    const YAML::Node region = message_.yaml.required(position, "constraint_region", where);
    message_.yaml.checkKeys(region, where + ".constraint_region",
                            {"primitives", "primitive_poses", "meshes", "mesh_poses"});
    const YAML::Node poses = message_.yaml.required(region, "primitive_poses", where + ".constraint_region");
    if (!poses.IsSequence() || poses.size() == 0)
      message_.yaml.fail(poses, where + ".constraint_region.primitive_poses", "expected the target pose");
    Eigen::Vector3d target = frameOf(position["header"], where + ".header") *
                             message_.pose(poses[0], where + ".constraint_region.primitive_poses[0]").translation();

    const YAML::Node orientations = node["orientation_constraints"];
    if (!orientations || !orientations.IsSequence() || orientations.size() == 0)
      message_.yaml.fail(node, field, "a pose goal needs an orientation constraint besides the position constraint");
    const YAML::Node orientation = orientations[0];
    const std::string at = field + ".orientation_constraints[0]";
    message_.yaml.checkKeys(orientation, at,
                            {"header", "orientation", "link_name", "absolute_x_axis_tolerance",
                             "absolute_y_axis_tolerance", "absolute_z_axis_tolerance", "parameterization", "weight"});
    const std::string orientedLink =
        message_.yaml.text(message_.yaml.required(orientation, "link_name", at), at + ".link_name");
    if (orientedLink != link)
      message_.yaml.fail(orientation["link_name"], at + ".link_name",
                         "expected the position constraint's link '" + link + "'");
    const Eigen::Matrix3d rotation =
        frameOf(orientation["header"], at + ".header").linear() *
        message_.quaternion(message_.yaml.required(orientation, "orientation", at), at + ".orientation").matrix();

    Eigen::Isometry3d linkPose = Eigen::Isometry3d::Identity();
    linkPose.linear() = rotation;
    linkPose.translation() = target;
    if (const auto offset = position["target_point_offset"])  // the point on the link that goes to the target
      linkPose.translation() -= rotation * message_.vector3(offset, where + ".target_point_offset");
    return robot::xyzRpyFromPose(problem_.baseInPlanningFrame.inverse() * linkPose * linkToTip);
  }

  Eigen::Isometry3d frameOf(const YAML::Node& header, const std::string& field) const {
    if (!header || header.IsNull()) return Eigen::Isometry3d::Identity();
    message_.yaml.checkKeys(header, field, {"seq", "stamp", "frame_id"});
    const YAML::Node frame = header["frame_id"];
    if (!frame || frame.IsNull()) return Eigen::Isometry3d::Identity();
    const std::string name = message_.yaml.text(frame, field + ".frame_id");
    if (name.empty() || name == frames_.root() || name == "world") return Eigen::Isometry3d::Identity();
    message_.yaml.fail(frame, field + ".frame_id",
                       "a goal is read in the planning frame '" + frames_.root() + "' (or 'world')");
  }

  // Pose of the tip in `link`, which must move rigidly with it (no moving joint in between).
  Eigen::Isometry3d rigidTransformToTip(const std::string& link, const YAML::Node& node,
                                        const std::string& field) const {
    const auto& links = model_.links();
    Eigen::Isometry3d tipInLink = Eigen::Isometry3d::Identity();
    for (int l = model_.tipLink(); l >= 0; l = links[l].parent) {
      if (links[l].name == link) return tipInLink;
      if (links[l].joint >= 0) break;
      tipInLink = links[l].originInParent * tipInLink;
    }
    message_.yaml.fail(node, field,
                       "link '" + link + "' does not move rigidly with the arm's tip '" + links[model_.tipLink()].name +
                           "' (a pose goal must name the flange or a link fixed to it)");
  }

  MessageReader message_;
  const robot::RobotModel& model_;
  const detail::UrdfFrames& frames_;
  MoveItProblem& problem_;
};

}  // namespace

MoveItProblem loadMoveItProblem(const std::filesystem::path& sceneFile, const std::filesystem::path& requestFile,
                                const MoveItRobot& robot) {
  // RViz's `.scene` text export or a PlanningScene YAML, told apart by the extension as MoveIt does.
  MoveItProblem problem =
      sceneFile.extension() == ".scene" ? loadMoveItTextScene(sceneFile, robot) : loadMoveItScene(sceneFile, robot);
  RequestReader(requestFile, *detail::sharedRobotModel(robot), *detail::sharedUrdfFrames(robot), problem).read();
  return problem;
}

}  // namespace arcplan::collision
