// Scenes and collision: load a scene file, validity of one configuration or of an (N, 6) batch (the
// batch API, GIL released), the colliding pairs, and distances with the closest pairs.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <string>
#include <vector>

#include "arcplan/collision/batch_check.h"
#include "arcplan/common/resources.h"
#include "bindings.h"
#include "errors.h"
#include "robot_handle.h"
#include "scene_handle.h"

namespace py = pybind11;

namespace arcplan::python {
namespace {

std::shared_ptr<SceneHandle> loadScene(const std::filesystem::path& file) {
  return std::make_shared<SceneHandle>(
      std::make_shared<const collision::Scene>(collision::loadScene(resolveDataPath(file))));
}

// One configuration (6,) -> bool; a batch (N, 6) -> N bools from the batch check.
py::object isValid(SceneHandle& scene, const py::handle& q) {
  const py::array array = py::array::ensure(q);
  if (array && array.ndim() == 2) {
    const DoubleArray rows = toJointRows(q, "Q");
    const auto states = asColumns(rows);  // the (N, 6) rows are the 6 x N columns, no copy
    std::vector<bool> free;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(scene.dataMutex);
      collision::areCollisionFree(*scene.model, *scene.data, states, free);
    }
    py::array_t<bool> result(static_cast<py::ssize_t>(free.size()));
    bool* out = result.mutable_data();
    for (std::size_t k = 0; k < free.size(); ++k) out[k] = free[k];
    return std::move(result);
  }
  const robot::Vector6 joints = toJoints(q, "q");
  py::gil_scoped_release release;
  std::lock_guard<std::mutex> lock(scene.dataMutex);
  return py::bool_(collision::isCollisionFree(*scene.model, *scene.data, joints));
}

template <typename Query>
auto withWorkspace(SceneHandle& scene, const py::handle& q, Query query) {
  const robot::Vector6 joints = toJoints(q, "q");
  py::gil_scoped_release release;
  std::lock_guard<std::mutex> lock(scene.dataMutex);
  return query(*scene.model, *scene.data, joints);
}

std::vector<std::string> queryNames(const SceneHandle& scene) {
  std::vector<std::string> names;
  for (const auto& query : scene.scene->queries) names.push_back(query.name);
  return names;
}

}  // namespace

void bindCollision(py::module_& module) {
  py::class_<collision::DistanceReport>(module, "Distance", "Minimum distances of one configuration (m).")
      .def_readonly("obstacle_distance", &collision::DistanceReport::obstacleDistance,
                    "robot-obstacle minimum; 0 in contact, inf without obstacles")
      .def_readonly("obstacle_pair", &collision::DistanceReport::obstaclePair, "(link, obstacle) of that minimum")
      .def_readonly("self_distance", &collision::DistanceReport::selfDistance, "between links (non-allowed pairs)")
      .def_readonly("self_pair", &collision::DistanceReport::selfPair, "(link, link) of that minimum")
      .def_property_readonly("minimum", &collision::DistanceReport::minimum, "closest pair of any kind")
      .def_property_readonly("clearance", &collision::clearanceOf,
                             "largest clearance the state meets: obstacle distance, self pairs only below 1 mm")
      .def("__repr__", [](const collision::DistanceReport& d) {
        return "<arcplan.Distance obstacle " + std::to_string(d.obstacleDistance) + " m (" + d.obstaclePair.first +
               "-" + d.obstaclePair.second + "), self " + std::to_string(d.selfDistance) + " m>";
      });

  py::class_<SceneHandle, std::shared_ptr<SceneHandle>>(module, "Scene",
                                                        "A planning scene with its robot and collision model.")
      .def_property_readonly("name", [](const SceneHandle& s) { return s.scene->name; })
      .def_property_readonly("source_file", [](const SceneHandle& s) { return s.scene->sourceFile; })
      .def_property_readonly("query_names", &queryNames)
      .def_property_readonly("obstacle_names", [](const SceneHandle& s) { return s.model->obstacleNames(); })
      .def_property_readonly("link_names", [](const SceneHandle& s) { return s.model->linkNames(); })
      .def_property_readonly(
          "robot",
          [](const SceneHandle& s) {
            // Shares ownership of the collision model, which owns the robot.
            return std::make_shared<RobotHandle>(std::shared_ptr<const robot::RobotModel>(s.model, &s.model->robot()));
          })
      .def("is_valid", &isValid, py::arg("q"),
           "Collision-free? q (6,) gives a bool; Q (N, 6) gives N bools (numpy.bool_), checked as a batch.")
      .def(
          "collisions",
          [](SceneHandle& s, const py::handle& q) { return withWorkspace(s, q, collision::collide).collisions; },
          py::arg("q"), "Every colliding (link, obstacle) or (link, link) pair at q (6,).")
      .def(
          "distance", [](SceneHandle& s, const py::handle& q) { return withWorkspace(s, q, collision::distance); },
          py::arg("q"), "Minimum robot-obstacle and robot-robot distances at q (6,) with their closest pairs.")
      .def("__repr__", [](const SceneHandle& s) {
        return "<arcplan.Scene " + s.scene->name + ", " + std::to_string(s.scene->obstacles.size()) + " obstacles, " +
               std::to_string(s.scene->queries.size()) + " queries>";
      });

  module.def("load_scene", &loadScene, py::arg("scene_file"),
             "Reads a scene YAML (a path, or a name under arcplan's data folder such as "
             "'scenes/thesis_obstacle.yaml') and builds its collision model.");
}

}  // namespace arcplan::python
