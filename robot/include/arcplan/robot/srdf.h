#pragma once
// The part of a MoveIt SRDF (semantic robot description) arcplan uses: the <disable_collisions>
// pairs, links that need not be checked against each other (adjacent, or never in contact).
#include <filesystem>
#include <string>
#include <vector>

namespace arcplan::robot {

struct DisabledCollision {
  std::string link1, link2;
  std::string reason;  // "Adjacent", "Never", … (may be empty)
  int line = 0;        // in the SRDF file, for messages
};

// Throws arcplan::Error with file:line for text that is not XML, a root that is not <robot>, or a
// <disable_collisions> without link1 or link2.
std::vector<DisabledCollision> loadSrdfDisabledCollisions(const std::filesystem::path& srdfFile);
std::vector<DisabledCollision> parseSrdfDisabledCollisions(const std::string& srdfXml,
                                                           const std::filesystem::path& sourceFile);

}  // namespace arcplan::robot
