#pragma once
// Internal to arcplan::collision: a map that keeps at most `capacity` entries, dropping the least
// recently used first. The per-process caches of mesh parts (mesh_part_cache.cpp) and of parsed robot
// descriptions (moveit_reading.cpp) use it, so a long session that loads one robot after another keeps
// a bounded number of them. Not thread-safe: each cache guards it with its own mutex.
#include <cstddef>
#include <iterator>
#include <list>
#include <map>
#include <utility>

namespace arcplan::collision::detail {

template <typename Key, typename Value>
class LruCache {
public:
  explicit LruCache(std::size_t capacity) : capacity_(capacity) {}

  // The entry of `key`, now the most recently used; nullptr when there is none.
  Value* find(const Key& key) {
    const auto found = entries_.find(key);
    if (found == entries_.end()) return nullptr;
    order_.splice(order_.end(), order_, found->second);
    return &found->second->second;
  }

  // The entry of `key`, made from `value` unless there is one already (then `value` is dropped); the
  // least recently used entry goes when there are more than `capacity`.
  Value& insert(const Key& key, Value value) {
    if (Value* existing = find(key)) return *existing;
    order_.emplace_back(key, std::move(value));
    entries_[key] = std::prev(order_.end());
    if (order_.size() > capacity_) {
      entries_.erase(order_.front().first);
      order_.pop_front();
    }
    return order_.back().second;
  }

  std::size_t size() const { return order_.size(); }

private:
  std::size_t capacity_;
  std::list<std::pair<Key, Value>> order_;  // least recently used first
  std::map<Key, typename std::list<std::pair<Key, Value>>::iterator> entries_;
};

}  // namespace arcplan::collision::detail
