// The `arcplan` Python module: thin bindings over the C++ library (docs/python.md). Each part is
// bound in its own file (bindings.h); the package's __init__.py re-exports everything.
#include <ompl/util/Console.h>
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "errors.h"

PYBIND11_MODULE(_arcplan, module) {
  module.doc() = "arcplan: arc planning, collision checking, PCHIP time scaling and robot models for UR arms";
  // As `arcplan` without --verbose: OMPL's informational lines would flood notebooks and loops.
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  arcplan::python::bindErrors(module);
  arcplan::python::bindRobot(module);
  arcplan::python::bindCollision(module);
  arcplan::python::bindTrajectory(module);
  arcplan::python::bindPlanning(module);
  arcplan::python::bindModel(module);
  arcplan::python::bindBenchmarks(module);
}
