#pragma once
// A UR arm straight from Universal Robots' own description parameters (the layout of
// UniversalRobots/Universal_Robots_ROS2_Description): config/<type>/default_kinematics.yaml (the
// joint frames, in the format a real robot's factory calibration is extracted to),
// physical_parameters.yaml (masses, centres of mass, inertias), joint_limits.yaml,
// visual_parameters.yaml (which collision mesh each link uses) and meshes/. The robot is assembled
// with the frame conventions of UR's xacro macro: base_link, base_link_inertia (turned by pi about
// z), shoulder_link … wrist_3_link, ft_frame, base, flange and tool0.
#include <filesystem>
#include <string>
#include <vector>

#include "arcplan/robot/robot_model.h"

namespace arcplan::robot {

struct UrDescriptionSelection {
  std::string type;                  // "ur5e": config/<type>/ in the folder
  std::filesystem::path folder;      // empty: defaultUrDescriptionFolder()
  std::filesystem::path kinematics;  // a calibration file; empty: config/<type>/default_kinematics.yaml
};

// $ARCPLAN_SHARED_DATA/ur_description (see common/resources.h).
std::filesystem::path defaultUrDescriptionFolder();

// The types a description folder holds (config/<type>/default_kinematics.yaml), sorted.
std::vector<std::string> urTypesIn(const std::filesystem::path& folder);

// The arm of that type; with a kinematics file its joint frames come from it and the model is
// calibrated(). Throws arcplan::Error with file:line:column and field for a bad file, and listing
// the known types for an unknown one.
RobotModel loadUrDescription(const UrDescriptionSelection& selection, const ChainSelection& chain = {});

}  // namespace arcplan::robot
