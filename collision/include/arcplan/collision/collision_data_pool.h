#pragma once
// CollisionData workspaces for callers on several threads (OMPL's PRM, for one, checks states from
// a roadmap thread and the solve thread at once): each caller leases a workspace for one query, so
// no two threads ever share one, and workspaces are reused instead of reallocated.
#include <memory>
#include <mutex>
#include <vector>

#include "arcplan/collision/collision_model.h"

namespace arcplan::collision {

class CollisionDataPool {
public:
  explicit CollisionDataPool(std::shared_ptr<const CollisionModel> model);

  // Exclusive use of one workspace until the lease is destroyed.
  class Lease {
  public:
    Lease(const CollisionDataPool& pool, std::unique_ptr<CollisionData> data);
    Lease(Lease&&) = default;
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    Lease& operator=(Lease&&) = delete;
    ~Lease();
    CollisionData& operator*() const { return *data_; }

  private:
    const CollisionDataPool* pool_;
    std::unique_ptr<CollisionData> data_;
  };

  Lease lease() const;
  const CollisionModel& model() const { return *model_; }
  const std::shared_ptr<const CollisionModel>& modelPointer() const { return model_; }

private:
  std::shared_ptr<const CollisionModel> model_;
  mutable std::mutex mutex_;
  mutable std::vector<std::unique_ptr<CollisionData>> idle_;
};

}  // namespace arcplan::collision
