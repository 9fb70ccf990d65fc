#include "arcplan/collision/allowed_collisions.h"

#include <set>

#include "arcplan/common/error.h"
#include "arcplan/common/yaml_reading.h"
#include "arcplan/common/resources.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/robot/srdf.h"

namespace arcplan::collision {
namespace {

std::pair<std::string, std::string> ordered(const std::string& first, const std::string& second) {
  return first < second ? std::make_pair(first, second) : std::make_pair(second, first);
}

bool isBuiltInUr10e(const robot::RobotModel& model) {
  std::error_code error;
  return std::filesystem::equivalent(model.sourceFile(), robot::ur10eUrdfPath(), error) && !error;
}

}  // namespace

void AllowedCollisionMatrix::allow(const std::string& first, const std::string& second) {
  pairs_.insert(ordered(first, second));
}

void AllowedCollisionMatrix::allow(const AllowedCollisionMatrix& other) {
  pairs_.insert(other.pairs_.begin(), other.pairs_.end());
}

bool AllowedCollisionMatrix::isAllowed(const std::string& first, const std::string& second) const {
  return pairs_.count(ordered(first, second)) > 0;
}

std::vector<std::pair<std::string, std::string>> AllowedCollisionMatrix::pairs() const {
  return {pairs_.begin(), pairs_.end()};
}

AllowedCollisionMatrix adjacentLinkPairs(const robot::RobotModel& model) {
  AllowedCollisionMatrix allowed;
  const auto& links = model.links();
  for (const auto& link : links) {
    if (link.collisions.empty()) continue;
    int ancestor = link.parent;
    while (ancestor >= 0 && links[ancestor].collisions.empty()) ancestor = links[ancestor].parent;
    if (ancestor >= 0) allowed.allow(link.name, links[ancestor].name);
  }
  return allowed;
}

AllowedCollisionMatrix loadAllowedCollisions(const std::filesystem::path& file) {
  const YamlReader yaml(file);
  const YAML::Node root = yaml.load("allowed-collisions file");
  if (!root.IsMap()) yaml.fail(root, "allowed-collisions file", "expected a mapping with key allowed_collisions");
  yaml.checkKeys(root, "allowed-collisions file", {"robot", "generator", "allowed_collisions"});
  const YAML::Node entries = yaml.required(root, "allowed_collisions", "allowed-collisions file");
  yaml.expectSequence(entries, "allowed_collisions");
  AllowedCollisionMatrix allowed;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const std::string field = "allowed_collisions[" + std::to_string(i) + "]";
    YAML::Node pair = entries[i];
    if (pair.IsMap()) {
      yaml.checkKeys(pair, field, {"links", "reason", "collisions", "min_distance"});
      pair = yaml.required(pair, "links", field);
    }
    if (!pair.IsSequence() || pair.size() != 2) yaml.fail(pair, field, "expected a pair [link, link]");
    allowed.allow(yaml.text(pair[0], field + "[0]"), yaml.text(pair[1], field + "[1]"));
  }
  return allowed;
}

std::filesystem::path ur10eAllowedCollisionsPath() { return dataDirectory() / "ur10e" / "allowed_collisions.yaml"; }

AllowedCollisionMatrix defaultAllowedCollisions(const robot::RobotModel& model) {
  AllowedCollisionMatrix allowed = adjacentLinkPairs(model);
  if (isBuiltInUr10e(model)) allowed.allow(loadAllowedCollisions(ur10eAllowedCollisionsPath()));
  return allowed;
}

AllowedCollisionMatrix srdfAllowedCollisions(const std::filesystem::path& srdfFile, const robot::RobotModel& model) {
  std::set<std::string> links;
  for (const auto& link : model.links()) links.insert(link.name);
  AllowedCollisionMatrix allowed;
  for (const auto& pair : robot::loadSrdfDisabledCollisions(srdfFile)) {
    for (const auto* name : {&pair.link1, &pair.link2}) {
      if (links.count(*name) == 0) {
        throw Error(std::filesystem::absolute(srdfFile).string() + ":" + std::to_string(pair.line) + ": link '" +
                    *name + "' is not a link of robot '" + model.name() +
                    "' (links: " + joinText({links.begin(), links.end()}, ", ") + ")");
      }
    }
    allowed.allow(pair.link1, pair.link2);
  }
  return allowed;
}

AllowedCollisionMatrix robotAllowedCollisions(const robot::RobotModel& model, const std::filesystem::path& srdfFile) {
  return srdfFile.empty() ? defaultAllowedCollisions(model) : srdfAllowedCollisions(srdfFile, model);
}

}  // namespace arcplan::collision
