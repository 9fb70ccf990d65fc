#pragma once
// Scene obstacles built in code, for tests that place a body at a known spot.
#include <string>

#include <Eigen/Geometry>

#include "arcplan/collision/scene.h"

namespace arcplan::testing {

// An unrotated obstacle of `shape` centred at `center`; its dimensions are set by the builders below.
inline collision::Obstacle placedAt(const std::string& name, collision::Obstacle::Shape shape,
                                    const Eigen::Vector3d& center) {
  collision::Obstacle obstacle;
  obstacle.name = name;
  obstacle.shape = shape;
  obstacle.pose.translation() = center;
  return obstacle;
}

inline collision::Obstacle sphere(const std::string& name, const Eigen::Vector3d& center, double radius) {
  collision::Obstacle obstacle = placedAt(name, collision::Obstacle::Shape::Sphere, center);
  obstacle.radius = radius;
  return obstacle;
}

inline collision::Obstacle box(const std::string& name, const Eigen::Vector3d& center, const Eigen::Vector3d& size) {
  collision::Obstacle obstacle = placedAt(name, collision::Obstacle::Shape::Box, center);
  obstacle.size = size;
  return obstacle;
}

}  // namespace arcplan::testing
