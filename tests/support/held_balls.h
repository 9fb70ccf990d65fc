#pragma once
// Two balls held by arcplan's UR10e in the thesis workcell (table only), a self pair whose distance is known from
// forward kinematics alone: for tests of what a clearance asks of the robot's own bodies (docs/collision.md,
// "Clearance"). Ball A is held by wrist_3_link, kHeld from its origin along its z axis; ball B by wrist_1_link. On
// a motion of the wrist-2 joint alone A turns about that joint's axis and B stands still, so the pair's distance
// is |c_A − c_B| − 2 r. B is placed 2 mm ahead of A's place at wrist-2 angle θ1 (on the tangent of A's circle),
// so A approaches B as the angle grows towards θ1 and runs into it beyond.
#include <memory>
#include <string>

#include <Eigen/Geometry>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/scene.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::testing {

class HeldBalls {
public:
  static constexpr double kBallRadius = 0.02;  // m, both balls
  static constexpr double kHeld = 0.10;        // m, ball A's centre from wrist_3_link's origin along its z axis
  static constexpr double kLead = 0.002;       // m, the balls' distance at θ1
  static constexpr double kWristStep = 2e-4;   // rad, the grid on which angleWhere looks for a distance

  HeldBalls() {
    const collision::Scene base = collision::loadScene(dataDirectory() / "scenes" / "thesis_free.yaml");
    robot_ = collision::makeCollisionModel(base)->sharedRobot();
    q1_ << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098;  // the scene's start, elbow up, wrist down
    const Eigen::Vector3d b = centreB();
    scene_ = base;
    scene_.attachedObstacles.push_back(ball("ball_a", "wrist_3_link", Eigen::Vector3d(0.0, 0.0, kHeld)));
    scene_.attachedObstacles.push_back(ball("ball_b", "wrist_1_link", poseOf("wrist_1_link", q1_).inverse() * b));
    for (const char* link : {"wrist_2_link", "wrist_3_link"}) scene_.allowedCollisions.emplace_back("ball_a", link);
    for (const char* link : {"wrist_1_link", "wrist_2_link"}) scene_.allowedCollisions.emplace_back("ball_b", link);
  }

  const collision::Scene& scene() const { return scene_; }
  // The scene's start with the wrist-2 joint at `wrist2`.
  robot::Vector6 at(double wrist2) const {
    robot::Vector6 q = q1_;
    q[4] = wrist2;
    return q;
  }
  // The balls' distance at wrist-2 angle `wrist2` [m].
  double gap(double wrist2) const { return (centreA(wrist2) - centreB()).norm() - 2 * kBallRadius; }
  // The wrist-2 angle nearest to θ1 on the side `direction` (+1: beyond θ1) where the gap first passes `wanted`.
  double angleWhere(double wanted, int direction) const {
    double angle = q1_[4];
    while (direction < 0 ? gap(angle) < wanted : gap(angle) > wanted) angle += direction * kWristStep;
    return angle;
  }

private:
  static collision::AttachedObstacle ball(const std::string& name, const std::string& link, const Eigen::Vector3d& at) {
    collision::AttachedObstacle held;
    held.link = link;
    held.body.name = name;
    held.body.shape = collision::Obstacle::Shape::Sphere;
    held.body.radius = kBallRadius;
    held.body.pose.translation() = at;
    return held;
  }
  Eigen::Isometry3d poseOf(const std::string& link, const robot::Vector6& q) const {
    robot::KinematicsData poses(*robot_);
    robot::forwardKinematics(*robot_, q, poses);
    return poses.linkPoses[robot_->linkIndex(link)];
  }
  Eigen::Vector3d centreA(double wrist2) const {
    return poseOf("wrist_3_link", at(wrist2)) * Eigen::Vector3d(0, 0, kHeld);
  }
  Eigen::Vector3d centreB() const {
    const Eigen::Vector3d tangent = (centreA(q1_[4] + 1e-6) - centreA(q1_[4] - 1e-6)).normalized();
    return centreA(q1_[4]) + (2 * kBallRadius + kLead) * tangent;
  }

  std::shared_ptr<const robot::RobotModel> robot_;
  robot::Vector6 q1_;
  collision::Scene scene_;
};

}  // namespace arcplan::testing
