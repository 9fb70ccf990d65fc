// Time scaling: arcplan.scale runs trajectory::scaleToTcpSpeed and computeMetrics, as `arcplan scale`
// does, with the GIL released; the trajectory's samples come back as arrays.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>
#include <vector>

#include "arcplan/trajectory/time_scaling.h"
#include "bindings.h"
#include "errors.h"
#include "json_objects.h"
#include "robot_handle.h"
#include "trajectory_objects.h"

namespace py = pybind11;

namespace arcplan::python {
namespace {

template <int Size>
py::array_t<double> rowsOf(const std::vector<Eigen::Matrix<double, Size, 1>>& vectors) {
  py::array_t<double> array({static_cast<py::ssize_t>(vectors.size()), py::ssize_t{Size}});
  double* out = array.mutable_data();
  for (const auto& v : vectors) out = std::copy(v.data(), v.data() + Size, out);
  return array;
}

py::array_t<double> valuesOf(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

TrajectoryHandle scale(const RobotHandle& robot, const py::handle& path, double maxTcpSpeed, double riseTime,
                       const std::optional<double>& maxTcpAcceleration) {
  const DoubleArray rows = toJointRows(path, "path");
  trajectory::JointPath joints(static_cast<std::size_t>(rows.shape(0)));
  for (std::size_t i = 0; i < joints.size(); ++i) joints[i] = Eigen::Map<const robot::Vector6>(rows.data() + 6 * i);
  trajectory::TimeScalingOptions options;
  options.maxTcpSpeed = maxTcpSpeed;
  options.riseTime = riseTime;
  options.maxTcpAcceleration = maxTcpAcceleration;
  py::gil_scoped_release release;
  TrajectoryHandle scaled{trajectory::scaleToTcpSpeed(*robot.model, joints, options), {}};
  scaled.metrics = trajectory::computeMetrics(joints, scaled.timed);
  return scaled;
}

}  // namespace

void bindTrajectory(py::module_& module) {
  using T = TrajectoryHandle;
  py::class_<T>(module, "Trajectory",
                "A time-scaled joint trajectory (PCHIP): samples on a uniform time grid, knots, metrics.")
      .def_property_readonly(
          "time", [](const T& t) { return valuesOf(t.timed.time); }, "sample times (s), (M,)")
      .def_property_readonly(
          "q", [](const T& t) { return rowsOf(t.timed.position); }, "positions (rad), (M, 6)")
      .def_property_readonly(
          "qd", [](const T& t) { return rowsOf(t.timed.velocity); }, "velocities (rad/s), (M, 6)")
      .def_property_readonly(
          "qdd", [](const T& t) { return rowsOf(t.timed.acceleration); }, "accelerations (rad/s^2), (M, 6)")
      .def_property_readonly(
          "tcp_speed", [](const T& t) { return valuesOf(t.timed.tcpSpeed); }, "(m/s), (M,)")
      .def_property_readonly(
          "tcp_position", [](const T& t) { return rowsOf(t.timed.tcpPosition); }, "(m, base frame), (M, 3)")
      .def_property_readonly("knot_times", [](const T& t) { return valuesOf(t.timed.knotTimes); })
      .def_property_readonly("knots", [](const T& t) { return rowsOf(t.timed.knots); })
      .def_property_readonly("dense_path", [](const T& t) { return rowsOf(t.timed.densePath); })
      .def_property_readonly(
          "duration", [](const T& t) { return t.timed.duration(); }, "(s)")
      .def_property_readonly(
          "tcp_path_length", [](const T& t) { return t.timed.tcpPathLength; }, "(m)")
      .def_property_readonly(
          "tcp_speed_limit", [](const T& t) { return t.timed.tcpSpeedLimit; }, "(m/s)")
      .def_property_readonly("joint_speed_limits",
                             [](const T& t) -> robot::Vector6 { return t.timed.jointSpeedLimits; })
      .def_property_readonly(
          "metrics", [](const T& t) { return toPython(trajectory::toJson(t.metrics)); },
          "The metrics under the keys of `arcplan scale --json` (None where not computed).")
      .def("__repr__", [](const T& t) {
        return "<arcplan.Trajectory " + std::to_string(t.timed.time.size()) + " samples, " +
               std::to_string(t.timed.duration()) + " s>";
      });

  module.def("scale", &scale, py::arg("robot"), py::arg("path"), py::kw_only(), py::arg("vmax") = 0.25,
             py::arg("rise_time") = 0.2, py::arg("max_tcp_acceleration") = py::none(),
             "Time-scales a joint path (N, 6) under a TCP speed limit vmax (m/s) with PCHIP, as `arcplan scale` "
             "does: ramp over rise_time (or at max_tcp_acceleration m/s^2), cruise, brake; slower where a joint "
             "speed limit requires it.");
}

}  // namespace arcplan::python
