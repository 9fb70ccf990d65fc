#include "moveit_scene_building.h"

#include <algorithm>

#include "arcplan/common/error.h"

namespace arcplan::collision::detail {

SceneBuilder::SceneBuilder(const MoveItRobot& robot, const std::filesystem::path& sourceFile)
    : robot_(robot),
      sourceFile_(sourceFile),
      model_(sharedRobotModel(robot)),
      frames_(sharedUrdfFrames(robot)),
      name_(sourceFile.stem().string()) {}

void SceneBuilder::addFixedFrame(const std::string& name, const Eigen::Isometry3d& poseInPlanningFrame) {
  fixedFrames_[name] = poseInPlanningFrame;
}

std::optional<Eigen::Isometry3d> SceneBuilder::frameInPlanningFrame(std::string frame) const {
  if (!frame.empty() && frame.front() == '/') frame.erase(0, 1);  // ROS 1 frames may carry a leading slash
  if (const auto fixed = fixedFrames_.find(frame); fixed != fixedFrames_.end()) return fixed->second;
  if (frame.empty() || frame == frames_->root() || frame == "world") return Eigen::Isometry3d::Identity();
  if (frames_->hasLink(frame)) return frames_->linkInRoot(frame, joints_);
  return std::nullopt;
}

bool SceneBuilder::addObject(const std::string& id, std::vector<Obstacle> shapes, const std::string& attachedTo,
                             const std::vector<std::string>& touchLinks) {
  if (frames_->hasLink(id)) {
    problem_ = "object '" + id + "' has the name of a link of the robot";
    return false;
  }
  if (!attachedTo.empty() && bodiesOf(attachedTo).empty()) {
    problem_ = "object '" + id + "' is attached to link '" + attachedTo +
               "', which is not in arcplan's model of the arm (its chain and the links fixed to it)";
    return false;
  }
  auto found = objects_.find(id);
  if (found != objects_.end() && found->second.link != attachedTo) {
    problem_ = "object '" + id + "' is given twice, attached to different links";
    return false;
  }
  if (found == objects_.end()) {
    objectOrder_.push_back(id);
    found = objects_.emplace(id, Object{{}, attachedTo}).first;
  }
  for (auto& shape : shapes) found->second.shapes.push_back(std::move(shape));  // APPEND, or one id written twice
  if (!attachedTo.empty()) {
    allow(id, attachedTo);
    for (const auto& link : touchLinks) allow(id, link);
  }
  return true;
}

bool SceneBuilder::isKnownName(const std::string& name) const {
  return frames_->hasLink(name) || objects_.count(name) != 0;
}

void SceneBuilder::allow(const std::string& first, const std::string& second) {
  if (first != second) allowed_.emplace(std::min(first, second), std::max(first, second));
}

void SceneBuilder::allowWithEverything(const std::string& name) { everything_.push_back(name); }

std::vector<std::string> SceneBuilder::bodiesOf(const std::string& name) const {
  if (const auto found = objects_.find(name); found != objects_.end()) {
    std::vector<std::string> parts;
    for (std::size_t k = 0; k < found->second.shapes.size(); ++k)
      parts.push_back(partName(name, k, found->second.shapes.size()));
    return parts;
  }
  // Links outside arcplan's model (above the arm's base, or without a place in it) have no geometry
  // there, so pairs with them change nothing.
  for (const auto& link : model_->links()) {
    if (link.name == name) return {name};
  }
  return {};
}

MoveItProblem SceneBuilder::finish() {
  MoveItProblem problem;
  problem.baseInPlanningFrame = frames_->linkInRoot(model_->links()[model_->baseLink()].name, joints_);
  const Eigen::Isometry3d planningInBase = problem.baseInPlanningFrame.inverse();
  Scene& scene = problem.scene;
  scene.name = name_;
  scene.sourceFile = sourceFile_;
  scene.robot.urdf = robot_.urdf;
  scene.robot.srdf = robot_.srdf;
  if (robot_.urdf.empty()) {
    scene.robot.urType = robot_.urDescription.type;
    scene.robot.description = robot_.urDescription.folder;
    scene.robot.kinematics = robot_.urDescription.kinematics;
  }
  for (const auto& id : objectOrder_) {
    const Object& object = objects_.at(id);
    for (std::size_t k = 0; k < object.shapes.size(); ++k) {
      Obstacle shape = object.shapes[k];
      shape.name = partName(id, k, object.shapes.size());
      if (object.link.empty()) {
        shape.pose = planningInBase * shape.pose;
        scene.obstacles.push_back(std::move(shape));
      } else {
        shape.pose = frames_->linkInRoot(object.link, joints_).inverse() * shape.pose;
        scene.attachedObstacles.push_back({std::move(shape), object.link});
      }
    }
  }
  std::vector<std::string> all;
  for (const auto& link : model_->links()) all.push_back(link.name);
  for (const auto& id : objectOrder_) all.push_back(id);
  for (const auto& name : everything_) {
    for (const auto& other : all) allow(name, other);
  }
  for (const auto& [first, second] : allowed_) {
    for (const auto& a : bodiesOf(first)) {
      for (const auto& b : bodiesOf(second)) scene.allowedCollisions.emplace_back(a, b);
    }
  }
  problem.startState = joints_;
  problem.ignoredMatrixNames = ignored_;
  return problem;
}

}  // namespace arcplan::collision::detail
