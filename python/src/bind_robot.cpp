// Robots and kinematics: a robot from arcplan's UR10e, a URDF or UR's description parameters (the
// CLI's robot options), forward kinematics, the Jacobian and every inverse-kinematics solution.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <optional>

#include "arcplan/common/error.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/pose.h"
#include "arcplan/robot/robot_source.h"
#include "bindings.h"
#include "errors.h"
#include "robot_handle.h"

namespace py = pybind11;

namespace arcplan::python {
namespace {

std::shared_ptr<RobotHandle> loadRobot(const std::optional<std::string>& urdf, const std::optional<std::string>& urType,
                                       const std::optional<std::string>& description,
                                       const std::optional<std::string>& kinematics, const std::string& baseLink,
                                       const std::string& tipLink, const py::object& tcpOffset) {
  robot::RobotSource source;
  if (urdf && *urdf != "ur10e") source.urdf = *urdf;
  if (urType) source.urType = *urType;
  if (description) source.description = *description;
  if (kinematics) source.kinematics = *kinematics;
  if ((description || kinematics) && !urType) throw Error("description and kinematics need ur_type");
  if (urdf && urType) throw Error("give either a URDF or ur_type, not both");
  source.chain.baseLink = baseLink;
  source.chain.tipLink = tipLink;
  if (!tcpOffset.is_none()) source.chain.tcpOffset = toPose(tcpOffset, "tcp_offset");
  return std::make_shared<RobotHandle>(std::make_shared<const robot::RobotModel>(robot::loadRobot(source)));
}

int linkOf(const RobotHandle& robot, const std::optional<std::string>& link) {
  return link ? robot.model->linkIndex(*link) : robot.model->tipLink();
}

Eigen::Matrix4d forwardKinematics(const RobotHandle& robot, const py::handle& q,
                                  const std::optional<std::string>& link) {
  const robot::Vector6 joints = toJoints(q, "q");
  robot::KinematicsData data(*robot.model);
  robot::forwardKinematics(*robot.model, joints, data);
  return data.linkPoses[linkOf(robot, link)].matrix();
}

Eigen::Matrix<double, 6, 6> jacobianOf(const RobotHandle& robot, const py::handle& q,
                                       const std::optional<std::string>& link) {
  const robot::Vector6 joints = toJoints(q, "q");
  robot::KinematicsData data(*robot.model);
  robot::forwardKinematics(*robot.model, joints, data);
  return robot::jacobian(*robot.model, data, linkOf(robot, link));
}

Eigen::VectorXd limitsOf(const RobotHandle& robot, double robot::JointLimits::*member) {
  Eigen::VectorXd values(robot.model->dof());
  for (int j = 0; j < robot.model->dof(); ++j) values[j] = robot.model->joints()[j].limits.*member;
  return values;
}

}  // namespace

const robot::UrInverseKinematics& RobotHandle::ik() const {
  if (!inverseKinematics) inverseKinematics = std::make_shared<const robot::UrInverseKinematics>(*model);
  return *inverseKinematics;
}

void bindRobot(py::module_& module) {
  py::class_<RobotHandle, std::shared_ptr<RobotHandle>>(module, "Robot",
                                                        "A robot model (immutable): joints, links, kinematics.")
      .def_property_readonly("name", [](const RobotHandle& r) { return r.model->name(); })
      .def_property_readonly("dof", [](const RobotHandle& r) { return r.model->dof(); })
      .def_property_readonly("source_file", [](const RobotHandle& r) { return r.model->sourceFile(); })
      .def_property_readonly("joint_names",
                             [](const RobotHandle& r) {
                               std::vector<std::string> names;
                               for (const auto& joint : r.model->joints()) names.push_back(joint.name);
                               return names;
                             })
      .def_property_readonly("link_names",
                             [](const RobotHandle& r) {
                               std::vector<std::string> names;
                               for (const auto& link : r.model->links()) names.push_back(link.name);
                               return names;
                             })
      .def_property_readonly("tip_link", [](const RobotHandle& r) { return r.model->links()[r.model->tipLink()].name; })
      .def_property_readonly("lower_limits",
                             [](const RobotHandle& r) { return limitsOf(r, &robot::JointLimits::lower); })
      .def_property_readonly("upper_limits",
                             [](const RobotHandle& r) { return limitsOf(r, &robot::JointLimits::upper); })
      .def_property_readonly("velocity_limits",
                             [](const RobotHandle& r) { return limitsOf(r, &robot::JointLimits::velocity); })
      .def("fk", &forwardKinematics, py::arg("q"), py::arg("link") = py::none(),
           "Pose (4x4) of the TCP, or of the named link, in the base frame for joints q (6,).")
      .def("jacobian", &jacobianOf, py::arg("q"), py::arg("link") = py::none(),
           "Geometric Jacobian (6x6, rows: linear then angular) of the TCP or named link at q, base frame.")
      .def(
          "ik",
          [](const RobotHandle& r, const py::handle& pose) { return toArray(r.ik().solveAll(toPose(pose, "pose"))); },
          py::arg("pose"),
          "Every inverse-kinematics solution inside the joint limits, (K, 6); pose 4x4 or [x, y, z, roll, pitch, yaw].")
      .def(
          "ik_nearest",
          [](const RobotHandle& r, const py::handle& pose, const py::handle& seed) -> std::optional<robot::Vector6> {
            return r.ik().solveNearest(toPose(pose, "pose"), toJoints(seed, "seed"));
          },
          py::arg("pose"), py::arg("seed"), "The in-limit IK solution nearest to seed (6,), or None.")
      .def("__repr__", [](const RobotHandle& r) {
        return "<arcplan.Robot " + r.model->name() + ", " + std::to_string(r.model->dof()) + " joints, tip " +
               r.model->links()[r.model->tipLink()].name + ">";
      });

  module.def("load_robot", &loadRobot, py::arg("urdf") = py::none(), py::kw_only(), py::arg("ur_type") = py::none(),
             py::arg("description") = py::none(), py::arg("kinematics") = py::none(),
             py::arg("base_link") = "base_link", py::arg("tip_link") = "tool0", py::arg("tcp_offset") = py::none(),
             "A robot: arcplan's UR10e (no argument or 'ur10e'), a URDF file, or ur_type='ur5e' from UR's "
             "description parameters (description folder, calibration kinematics file), as the CLI's robot "
             "options; tip_link and tcp_offset ([x, y, z, roll, pitch, yaw]) choose the TCP.");
  module.def(
      "pose_from_xyz_rpy", [](const py::handle& xyzRpy) { return toPose(xyzRpy, "xyz_rpy").matrix(); },
      py::arg("xyz_rpy"), "[x, y, z, roll, pitch, yaw] (URDF fixed-axis RPY) as a 4x4 homogeneous matrix.");
}

}  // namespace arcplan::python
