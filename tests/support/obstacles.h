#pragma once
// Scene obstacles built in code, for tests that place a body at a known spot.
#include <string>

#include <Eigen/Geometry>

#include "arcplan/collision/scene.h"

namespace arcplan::testing {

inline collision::Obstacle sphere(const std::string& name, const Eigen::Vector3d& center, double radius) {
  collision::Obstacle obstacle;
  obstacle.name = name;
  obstacle.shape = collision::Obstacle::Shape::Sphere;
  obstacle.radius = radius;
  obstacle.pose.translation() = center;
  return obstacle;
}

inline collision::Obstacle box(const std::string& name, const Eigen::Vector3d& center, const Eigen::Vector3d& size) {
  collision::Obstacle obstacle;
  obstacle.name = name;
  obstacle.shape = collision::Obstacle::Shape::Box;
  obstacle.size = size;
  obstacle.pose.translation() = center;
  return obstacle;
}

}  // namespace arcplan::testing
