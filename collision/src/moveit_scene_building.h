#pragma once
// Internal to the MoveIt readers: collects objects (poses in MoveIt's planning frame), attached bodies
// and allowed pairs as the YAML and text readers find them, and turns them into arcplan's Scene, whose
// obstacles are in the arm's base_link and whose allowed pairs name only bodies the collision model has.
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "arcplan/collision/moveit_scene.h"
#include "arcplan/robot/robot_model.h"
#include "moveit_reading.h"

namespace arcplan::collision::detail {

class SceneBuilder {
public:
  SceneBuilder(const MoveItRobot& robot, const std::filesystem::path& sourceFile);

  const UrdfFrames& frames() const { return *frames_; }
  const robot::RobotModel& model() const { return *model_; }
  const std::map<std::string, double>& joints() const { return joints_; }

  void setName(const std::string& name) { name_ = name; }
  // The robot state: link frames, attached bodies and the start of a request default to it.
  void setJoints(std::map<std::string, double> joints) { joints_ = std::move(joints); }
  void addFixedFrame(const std::string& name, const Eigen::Isometry3d& poseInPlanningFrame);
  // The planning frame (the URDF root, "", "world"), a fixed frame or a link at the current joints.
  std::optional<Eigen::Isometry3d> frameInPlanningFrame(std::string frame) const;

  // Shapes with poses in the planning frame; attachedTo: the link holding them ("" for the world).
  // False (problem()) for an id that is already an object or a link.
  bool addObject(const std::string& id, std::vector<Obstacle> shapes, const std::string& attachedTo,
                 const std::vector<std::string>& touchLinks);
  const std::string& problem() const { return problem_; }

  bool isKnownName(const std::string& name) const;  // a URDF link or an object id
  void ignoreMatrixName(const std::string& name) { ignored_.push_back(name); }
  void allow(const std::string& first, const std::string& second);
  void allowWithEverything(const std::string& name);

  MoveItProblem finish();

private:
  std::vector<std::string> bodiesOf(const std::string& name) const;  // object parts, or the link itself

  MoveItRobot robot_;
  std::filesystem::path sourceFile_;
  std::shared_ptr<const robot::RobotModel> model_;
  std::shared_ptr<const UrdfFrames> frames_;
  std::string name_;
  std::map<std::string, double> joints_;
  std::map<std::string, Eigen::Isometry3d> fixedFrames_;
  struct Object {
    std::vector<Obstacle> shapes;
    std::string link;
  };
  std::map<std::string, Object> objects_;
  std::vector<std::string> objectOrder_;
  std::set<std::pair<std::string, std::string>> allowed_;
  std::vector<std::string> everything_;
  std::vector<std::string> ignored_;
  std::string problem_;
};

}  // namespace arcplan::collision::detail
