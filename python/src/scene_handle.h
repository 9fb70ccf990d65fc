#pragma once
// What arcplan.Scene holds: the scene as read, its collision model, and one collision workspace for
// the queries made through it. The workspace is used with the GIL released, so a mutex keeps two
// Python threads from sharing it at once.
#include <memory>
#include <mutex>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/scene.h"

namespace arcplan::python {

struct SceneHandle {
  explicit SceneHandle(std::shared_ptr<const collision::Scene> loaded)
      : scene(std::move(loaded)),
        model(collision::makeCollisionModel(*scene)),
        data(std::make_unique<collision::CollisionData>(*model)) {}

  std::shared_ptr<const collision::Scene> scene;
  std::shared_ptr<const collision::CollisionModel> model;
  std::unique_ptr<collision::CollisionData> data;
  std::mutex dataMutex;
};

}  // namespace arcplan::python
