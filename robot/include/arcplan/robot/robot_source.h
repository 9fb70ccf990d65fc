#pragma once
// Where a robot comes from, as a scene's `robot:` entry or the command line names it: a URDF file,
// or a UR type from Universal Robots' description folder (optionally with a calibration file); an
// SRDF with the pairs that need no collision check; the chain's base and TCP.
#include <filesystem>
#include <string>

#include "arcplan/robot/robot_model.h"

namespace arcplan::robot {

struct RobotSource {
  std::filesystem::path urdf;         // a URDF file; empty with urType empty: arcplan's built-in UR10e
  std::string urType;                 // "ur5e": built from a UR description folder (ur_description.h)
  std::filesystem::path description;  // that folder; empty: defaultUrDescriptionFolder()
  std::filesystem::path kinematics;   // a calibration file replacing config/<type>/default_kinematics.yaml
  std::filesystem::path srdf;         // <disable_collisions> pairs (read by collision/allowed_collisions.h)
  ChainSelection chain;               // base link, TCP link and offset

  // Neither a URDF nor a UR type: arcplan's built-in UR10e.
  bool isBuiltIn() const { return urdf.empty() && urType.empty(); }
};

// The robot the source names. Throws arcplan::Error as loadRobotModel / loadUrDescription do.
RobotModel loadRobot(const RobotSource& source);

}  // namespace arcplan::robot
