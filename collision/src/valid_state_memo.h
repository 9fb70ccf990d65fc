#pragma once
// The states a CollisionStateValidityChecker has found valid, so that asking again answers at once. OMPL's
// RRTConnect asks again for every motion of its goal tree: it checks the new state itself, then
// checkMotion(new, tree node), whose end (the tree node) the motion validator checks once more; the answer
// is a function of the joint values alone (the model and the required clearance at the state never change),
// so the memo cannot change it. Keys are the joint values' bytes: only the same state bit for bit is found.
// Internal to arcplan::collision: not installed. Safe to use from several threads.
#include <cstddef>
#include <mutex>
#include <string>
#include <unordered_set>

#include "arcplan/robot/kinematics.h"

namespace arcplan::collision::detail {

class ValidStateMemo {
public:
  bool contains(const robot::JointRef& q) const {
    const std::string key = keyOf(q);
    const std::lock_guard<std::mutex> lock(mutex_);
    return states_.count(key) > 0;
  }

  void insert(const robot::JointRef& q) {
    std::string key = keyOf(q);
    const std::lock_guard<std::mutex> lock(mutex_);
    // Bounded memory: a full memo starts again (a state found again is only measured again).
    if (states_.size() >= kCapacity) states_.clear();
    states_.insert(std::move(key));
  }

private:
  // A few times the trees RRTConnect grows in 10 s on MBM's bookshelves (up to 8500 states): about 4 MB.
  static constexpr std::size_t kCapacity = 1 << 15;

  static std::string keyOf(const robot::JointRef& q) {
    return std::string(reinterpret_cast<const char*>(q.data()), sizeof(double) * static_cast<std::size_t>(q.size()));
  }

  mutable std::mutex mutex_;
  std::unordered_set<std::string> states_;
};

}  // namespace arcplan::collision::detail
