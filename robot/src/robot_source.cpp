#include "arcplan/robot/robot_source.h"

#include "arcplan/robot/ur_description.h"

namespace arcplan::robot {

RobotModel loadRobot(const RobotSource& source) {
  if (!source.urType.empty()) {
    return loadUrDescription({source.urType, source.description, source.kinematics}, source.chain);
  }
  return loadRobotModel(source.urdf.empty() ? ur10eUrdfPath() : source.urdf, source.chain);
}

}  // namespace arcplan::robot
