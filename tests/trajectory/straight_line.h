#pragma once
// The thesis' straight TCP line A→B (case a) as a joint path: tool0 poses evenly spaced on the
// segment, joints by nearest analytic IK starting from the "elbow up, wrist down" seed.
#include <Eigen/Geometry>

#include "arcplan/robot/robot_model.h"
#include "arcplan/trajectory/joint_path.h"

namespace arcplan::trajectory::testing {

Eigen::Isometry3d thesisPoseA();
Eigen::Isometry3d thesisPoseB();
robot::Vector6 thesisSeedA();

// `segments` + 1 waypoints from A to B.
JointPath straightLinePath(const robot::RobotModel& model, int segments);

}  // namespace arcplan::trajectory::testing
