#pragma once
// The parts of the `arcplan` Python module, one function per part, each in its own source file and
// called once by module.cpp.
#include <pybind11/pybind11.h>

namespace arcplan::python {

void bindRobot(pybind11::module_& module);       // bind_robot.cpp: robots, FK, IK, Jacobian
void bindCollision(pybind11::module_& module);   // bind_collision.cpp: scenes, validity, distances
void bindPlanning(pybind11::module_& module);    // bind_planning.cpp: plan with any registry planner
void bindTrajectory(pybind11::module_& module);  // bind_trajectory.cpp: PCHIP time scaling, metrics
void bindModel(pybind11::module_& module);       // bind_model.cpp: the model loop (arcplan.model)
void bindBenchmarks(pybind11::module_& module);  // bind_benchmarks.cpp: suites, rankings (arcplan.bench)

}  // namespace arcplan::python
