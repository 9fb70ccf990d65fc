#include "arcplan/collision/collision_data_pool.h"

#include "arcplan/common/error.h"

namespace arcplan::collision {

CollisionDataPool::CollisionDataPool(std::shared_ptr<const CollisionModel> model) : model_(std::move(model)) {
  if (!model_) throw Error("collision data pool: no collision model");
}

CollisionDataPool::Lease::Lease(const CollisionDataPool& pool, std::unique_ptr<CollisionData> data)
    : pool_(&pool), data_(std::move(data)) {}

CollisionDataPool::Lease::~Lease() {
  if (!data_) return;  // moved from
  const std::lock_guard<std::mutex> lock(pool_->mutex_);
  pool_->idle_.push_back(std::move(data_));
}

CollisionDataPool::Lease CollisionDataPool::lease() const {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!idle_.empty()) {
      auto data = std::move(idle_.back());
      idle_.pop_back();
      return Lease(*this, std::move(data));
    }
  }
  return Lease(*this, std::make_unique<CollisionData>(*model_));
}

}  // namespace arcplan::collision
