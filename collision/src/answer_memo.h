#pragma once
// Answers remembered by the joint values they were computed for, so that asking again answers at once:
// the state validity checker keeps the states it found valid, the motion validator its motions' answers. Both
// answers are functions of the joint values alone (the model, the options and the required clearance of a
// checker or validator never change), so a memo cannot change them. Only the same joint values bit for bit are
// found. Internal to arcplan::collision: not installed. Safe to use from several threads.
//
// Who asks again: OMPL's RRTConnect checks every new state of its goal tree itself and then checkMotion(new,
// tree node), whose end the motion validator checks once more (a state); OMPL's simplifier tries the same
// shortcut again in each round of simplifyMax where the path did not change there, and the certified
// simplification (planners/certified_simplification.h) checks every motion of the result once more, most of them
// motions the planner checked (motions).
//
// Keys are the values themselves in a fixed array (no allocation to ask): RRTConnect's solve on the generated suite,
// whose motions take microseconds, pays about 2 % for the motion memo. Keys of their own (std::string of the bytes,
// a heap block per question) cost it 4.5 %, a table of slots chosen by hash (no allocation at all, but a random cache
// line of a megabyte per question) 15 %.
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <optional>
#include <unordered_map>

#include "arcplan/robot/kinematics.h"

namespace arcplan::collision::detail {

// `Parts` joint vectors per key: 1 for a state, 2 for a motion (its two ends).
template <typename Answer, int Parts>
class AnswerMemo {
public:
  using Key = std::array<const robot::JointRef*, Parts>;

  // The answer remembered for `key`, if any.
  std::optional<Answer> find(const Key& key) const {
    Values values;
    if (!fill(values, key)) return std::nullopt;
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto found = answers_.find(values);
    if (found == answers_.end()) return std::nullopt;
    return found->second;
  }

  void insert(const Key& key, const Answer& answer) {
    Values values;
    if (!fill(values, key)) return;  // more joints than a key holds: not remembered
    const std::lock_guard<std::mutex> lock(mutex_);
    // Bounded memory: a full memo starts again (what is asked again is only computed again).
    if (answers_.size() >= kCapacity) answers_.clear();
    answers_.emplace(values, answer);
  }

private:
  // Arms of up to 8 joints. States: a few times the trees RRTConnect grows in 10 s on MBM's bookshelves (up to 8500
  // states). Motions: the recent ones a simplification asks again; a memo of 32768 motions filled by thousands of
  // cheap plans made RRTConnect's solve on the thesis scene 8–30 % slower (its cache misses), one of 1024 does not.
  static constexpr std::size_t kMaxJoints = 8;
  static constexpr std::size_t kCapacity = std::size_t{1} << (Parts == 1 ? 15 : 10);

  // The bits of the key's joint values one after the other, the rest padded (a memo's keys all have its robot's joint
  // count).
  using Values = std::array<std::uint64_t, kMaxJoints * Parts>;

  static bool fill(Values& values, const Key& key) {
    std::size_t size = 0;
    for (const robot::JointRef* q : key) {
      const auto count = static_cast<std::size_t>(q->size());
      if (size + count > values.size()) return false;
      std::memcpy(values.data() + size, q->data(), sizeof(double) * count);
      size += count;
    }
    const double padding = std::numeric_limits<double>::quiet_NaN();
    for (; size < values.size(); ++size) std::memcpy(&values[size], &padding, sizeof padding);
    return true;
  }

  // FNV-1a over the values' bits, 64-bit words at a time.
  struct Hash {
    std::size_t operator()(const Values& values) const {
      std::uint64_t hash = 0xcbf29ce484222325ULL;
      for (const std::uint64_t bits : values) hash = (hash ^ bits) * 0x100000001b3ULL;
      return static_cast<std::size_t>(hash ^ (hash >> 32));
    }
  };

  mutable std::mutex mutex_;
  std::unordered_map<Values, Answer, Hash> answers_;
};

// A motion's answer: valid, or the fraction of it up to its last valid state (0 when that was not asked).
struct MotionAnswer {
  bool valid = false;
  double lastValidFraction = 0.0;
};

// A JointMotionValidator's answers (ompl_validity.h), one memo per checkMotion overload: where the last valid state is
// wanted nothing is deferred (motion_check.h), so on a motion at the edge of what the certificate accepts the two need
// not agree.
struct MotionMemo {
  AnswerMemo<MotionAnswer, 2> plain, traced;
};

}  // namespace arcplan::collision::detail
