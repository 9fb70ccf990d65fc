#include "errors.h"

#include <cmath>

#include <Eigen/Geometry>
#include <sstream>
#include <string>

#include "arcplan/common/error.h"
#include "arcplan/robot/pose.h"

namespace py = pybind11;

namespace arcplan::python {
namespace {

std::string shapeOf(const py::array& array) {
  std::ostringstream text;
  text << "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) text << (i ? ", " : "") << array.shape(i);
  text << (array.ndim() == 1 ? ",)" : ")");
  return text.str();
}

DoubleArray toDoubles(const py::handle& object, const char* what) {
  // ensure() returns a null array (error cleared) for what NumPy cannot turn into float64.
  DoubleArray array = DoubleArray::ensure(object);
  if (!array) {
    throw Error(std::string(what) + ": expected an array of numbers, got " +
                py::str(py::type::of(object).attr("__name__")).cast<std::string>());
  }
  return array;
}

void checkFinite(const DoubleArray& array, const char* what) {
  const double* values = array.data();
  for (py::ssize_t i = 0; i < array.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw Error(std::string(what) + ": element " + std::to_string(i) + " is " + std::to_string(values[i]) +
                  "; expected finite numbers");
    }
  }
}

}  // namespace

void bindErrors(py::module_& module) {
  // Derived from RuntimeError so that code catching that keeps working.
  static py::exception<Error> error(module, "Error", PyExc_RuntimeError);
  error.doc() = "Bad input or an impossible request; the message names the file:line or field and what was expected.";
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const Error& e) {
      error(e.what());
    }
  });
}

robot::Vector6 toJoints(const py::handle& object, const char* what) {
  const DoubleArray array = toDoubles(object, what);
  if (array.ndim() != 1 || array.shape(0) != 6)
    throw Error(std::string(what) + ": expected 6 joint values, shape (6,), got shape " + shapeOf(array));
  checkFinite(array, what);
  return Eigen::Map<const robot::Vector6>(array.data());
}

DoubleArray toJointRows(const py::handle& object, const char* what, bool allowEmpty) {
  DoubleArray array = toDoubles(object, what);
  if (array.ndim() != 2 || array.shape(1) != 6)
    throw Error(std::string(what) + ": expected an (N, 6) array of joint vectors, got shape " + shapeOf(array));
  if (!allowEmpty && array.shape(0) == 0) throw Error(std::string(what) + ": expected at least one row");
  checkFinite(array, what);
  return array;
}

Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>> asColumns(const DoubleArray& rows) {
  return {rows.data(), 6, static_cast<Eigen::Index>(rows.shape(0))};
}

Eigen::Isometry3d toPose(const py::handle& object, const char* what) {
  const DoubleArray array = toDoubles(object, what);
  checkFinite(array, what);
  if (array.ndim() == 1 && array.shape(0) == 6) {
    const double* v = array.data();
    return robot::poseFromXyzRpy({v[0], v[1], v[2], v[3], v[4], v[5]});
  }
  if (array.ndim() == 2 && array.shape(0) == 4 && array.shape(1) == 4) {
    const Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>> matrix(array.data());
    // A matrix that is not a rigid transform would give meaningless kinematics rather than an error.
    const Eigen::Matrix3d rotation = matrix.topLeftCorner<3, 3>();
    const bool rigid = (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm() < 1e-6 &&
                       rotation.determinant() > 0.0 && matrix.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-12);
    if (!rigid) throw Error(std::string(what) + ": the 4x4 matrix is not a rigid transform (rotation, translation)");
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.matrix() = matrix;
    return pose;
  }
  throw Error(std::string(what) + ": expected a 4x4 homogeneous matrix or [x, y, z, roll, pitch, yaw], got shape " +
              shapeOf(array));
}

DoubleArray toArray(const std::vector<robot::Vector6>& vectors) {
  DoubleArray array({static_cast<py::ssize_t>(vectors.size()), py::ssize_t{6}});
  double* out = array.mutable_data();
  for (const robot::Vector6& q : vectors) out = std::copy(q.data(), q.data() + 6, out);
  return array;
}

}  // namespace arcplan::python
