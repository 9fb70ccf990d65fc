#pragma once
// Which pairs of bodies (robot links, scene obstacles) may touch without counting as a collision:
// adjacent links (they share a joint housing), pairs that can never touch (found once by sampling,
// recorded in data/ur10e/allowed_collisions.yaml), and what a scene adds (the base on the table).
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "arcplan/robot/robot_model.h"

namespace arcplan::collision {

class AllowedCollisionMatrix {
public:
  void allow(const std::string& first, const std::string& second);
  void allow(const AllowedCollisionMatrix& other);
  bool isAllowed(const std::string& first, const std::string& second) const;
  // Every allowed pair once, each written (smaller name, larger name), sorted.
  std::vector<std::pair<std::string, std::string>> pairs() const;
  std::size_t size() const { return pairs_.size(); }

private:
  std::set<std::pair<std::string, std::string>> pairs_;
};

// Each link with collision geometry paired with its nearest ancestor that has collision geometry.
AllowedCollisionMatrix adjacentLinkPairs(const robot::RobotModel& model);

// Reads an allowed-collisions file: `allowed_collisions:` a list of `{links: [a, b], reason: ...}`
// or plain `[a, b]` pairs. Throws arcplan::Error with file, line and field on bad input.
AllowedCollisionMatrix loadAllowedCollisions(const std::filesystem::path& file);

// data/ur10e/allowed_collisions.yaml (written by arcplan_generate_allowed_collisions).
std::filesystem::path ur10eAllowedCollisionsPath();

// The <disable_collisions> pairs of an SRDF (robot/srdf.h). Throws arcplan::Error with file:line for
// a pair naming a link `model` does not have.
AllowedCollisionMatrix srdfAllowedCollisions(const std::filesystem::path& srdfFile, const robot::RobotModel& model);

// The robot's own allowed pairs: an SRDF's pairs when `srdfFile` is given (MoveIt's meaning: what the
// SRDF does not disable is checked), else defaultAllowedCollisions.
AllowedCollisionMatrix robotAllowedCollisions(const robot::RobotModel& model, const std::filesystem::path& srdfFile);

// Adjacent pairs; for arcplan's built-in UR10e also the recorded never-colliding pairs, which hold
// only for its own link meshes (a model loaded from another URDF gets the adjacent pairs alone).
AllowedCollisionMatrix defaultAllowedCollisions(const robot::RobotModel& model);

}  // namespace arcplan::collision
