#pragma once
// arcplan.Error, the one Python exception of the module: every arcplan::Error thrown below a binding
// becomes it, with arcplan's message (`file:line: what`). The array conversions here check what a
// binding receives (shape, finite values) and throw arcplan::Error too, so bad input never reaches
// the library as garbage and never crashes the interpreter.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>

#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::python {

void bindErrors(pybind11::module_& module);

// A C-contiguous float64 array (a copy only when `object` is another dtype or layout).
using DoubleArray = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;

// `object` as a (6,) joint vector of finite values; `what` names the argument in messages.
robot::Vector6 toJoints(const pybind11::handle& object, const char* what);

// An (N, 6) array of finite values; N >= 1 unless `allowEmpty`.
DoubleArray toJointRows(const pybind11::handle& object, const char* what, bool allowEmpty = true);

// The rows of an (N, 6) C-contiguous array as a 6 x N column-major matrix, without a copy.
Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>> asColumns(const DoubleArray& rows);

// A pose as a 4x4 homogeneous matrix or [x, y, z, roll, pitch, yaw] (URDF fixed-axis RPY, as scene
// files write poses).
Eigen::Isometry3d toPose(const pybind11::handle& object, const char* what);

// Rows of `vectors` as a new (N, 6) float64 array.
DoubleArray toArray(const std::vector<robot::Vector6>& vectors);

}  // namespace arcplan::python
