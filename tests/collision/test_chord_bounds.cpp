// chordMotionBound (collision/src/motion_bounds.h): the rate a path certifier takes from a link's poses at a motion's
// two ends. Checked against the link's own mesh vertices (loaded here from the URDF's files) placed by forward
// kinematics at 41 states along each motion: no vertex may move faster than the rate between any two of them.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "arcplan/collision/collision_model.h"
#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/mesh.h"
#include "motion_bounds.h"  // collision/src: the bounds behind the certified check

namespace {

using namespace arcplan::collision;
using Eigen::VectorXd;

std::shared_ptr<const CollisionModel> thesisFree() {
  return makeCollisionModel(loadScene(arcplan::dataDirectory() / "scenes" / "thesis_free.yaml"));
}

// Every collision-mesh vertex of link `body` (model.linkNames() order) in its link frame.
std::vector<Eigen::Vector3d> vertices(const CollisionModel& model, int body) {
  std::vector<Eigen::Vector3d> result;
  const auto& link = model.robot().links()[model.robot().linkIndex(model.linkNames()[body])];
  for (const auto& geometry : link.collisions) {
    for (const auto& v : arcplan::robot::loadMesh(geometry.meshFile, geometry.meshScale).vertices)
      result.push_back(geometry.origin * v);
  }
  return result;
}

// The largest speed of any vertex of `body` between neighbouring states of 40 equal pieces of qa -> qb, per unit of
// the motion's fraction (a lower estimate of the true largest speed, which it approaches as the pieces shrink).
double sampledSpeed(const CollisionModel& model, int body, const std::vector<Eigen::Vector3d>& points,
                    const VectorXd& qa, const VectorXd& qb) {
  constexpr int kPieces = 40;
  const auto& robot = model.robot();
  const int link = robot.linkIndex(model.linkNames()[body]);
  arcplan::robot::KinematicsData before(robot), after(robot);
  arcplan::robot::forwardKinematics(robot, qa, before);
  double fastest = 0.0;
  for (int k = 1; k <= kPieces; ++k) {
    arcplan::robot::forwardKinematics(robot, qa + (static_cast<double>(k) / kPieces) * (qb - qa), after);
    for (const auto& v : points)
      fastest = std::max(fastest, kPieces * (after.linkPoses[link] * v - before.linkPoses[link] * v).norm());
    std::swap(before, after);
  }
  return fastest;
}

TEST(ChordBounds, NoVertexMovesFasterThanTheRate) {
  const auto model = thesisFree();
  const auto& robot = model->robot();
  const int bodies = static_cast<int>(model->linkNames().size());
  std::vector<std::vector<Eigen::Vector3d>> points;
  for (int body = 0; body < bodies; ++body) points.push_back(vertices(*model, body));
  std::mt19937_64 random(29);
  std::vector<double> tightest(bodies, 0.0);  // per link, the largest sampled speed / rate on the small steps
  for (int trial = 0; trial < 120; ++trial) {
    VectorXd qa(6), dq(6);
    for (int j = 0; j < 6; ++j) {
      const auto& limits = robot.joints()[j].limits;
      qa[j] = std::uniform_real_distribution<double>(limits.lower, limits.upper)(random);
    }
    // Waypoint steps of a dense path (0.02 rad), a planner's edges (0.3 rad) and long motions (1.5 rad), where the
    // curvature of the links' paths, not their chords, sets the rate.
    const double size = trial % 3 == 0 ? 0.02 : trial % 3 == 1 ? 0.3 : 1.5;
    for (int j = 0; j < 6; ++j) dq[j] = std::uniform_real_distribution<double>(-size, size)(random);
    const VectorXd qb = qa + dq;
    for (int body = 0; body < bodies; ++body) {
      const double rate = chordMotionBound(*model, body, qa, qb);
      const double fastest = sampledSpeed(*model, body, points[body], qa, qb);
      ASSERT_LE(fastest, rate) << model->linkNames()[body] << " trial " << trial;
      if (size < 0.05 && rate > 0.0) tightest[body] = std::max(tightest[body], fastest / rate);
    }
  }
  // Not vacuous: on small steps some vertex of every moving link comes within a factor 2 of its rate.
  for (int body = 1; body < bodies; ++body) EXPECT_GT(tightest[body], 0.5) << model->linkNames()[body];
}

TEST(ChordBounds, AWholeTurnThatEndsWhereItStartedStillMoves) {
  // A full turn of the base joint: every link's pose is the same at both ends (a chord of zero), yet the flange
  // travels a circle about the base axis. Only the curvature term sees it: the rate must cover the circle's speed,
  // 2π times the flange's farthest vertex from the axis.
  const auto model = thesisFree();
  const auto& robot = model->robot();
  const int flange = static_cast<int>(model->linkNames().size()) - 1;
  const VectorXd qa = (VectorXd(6) << 0.0, -1.2, 1.4, -1.8, -1.571, 0.0).finished();
  VectorXd qb = qa;
  qb[0] += 2.0 * M_PI;
  arcplan::robot::KinematicsData data(robot);
  arcplan::robot::forwardKinematics(robot, qa, data);
  double farthest = 0.0;
  for (const auto& v : vertices(*model, flange))
    farthest = std::max(farthest, (data.linkPoses[robot.linkIndex(model->linkNames()[flange])] * v).head<2>().norm());
  EXPECT_GT(farthest, 0.3);
  EXPECT_GE(chordMotionBound(*model, flange, qa, qb), 2.0 * M_PI * farthest);
}

TEST(ChordBounds, DenseStepsGetARateBelowTheJointStepsBound) {
  // The reason the certifier takes it: on a step where the joints turn against each other (an elbow opening while the
  // shoulder lifts, as when the tool moves along a line) the links move far less than Σ_j |Δq_j| · reach_j says.
  const auto model = thesisFree();
  const int flange = static_cast<int>(model->linkNames().size()) - 1;
  const VectorXd qa = (VectorXd(6) << 0.3, -1.3, 1.6, -1.9, -1.571, 0.3).finished();
  VectorXd qb = qa;
  qb[1] += 0.01;  // shoulder lifts
  qb[2] -= 0.02;  // elbow opens
  qb[3] += 0.01;  // wrist keeps the tool's pitch
  const double jointSteps = motionBound(*model, flange, qa, qb);
  const double chord = chordMotionBound(*model, flange, qa, qb);
  EXPECT_LT(2.0 * chord, jointSteps) << "chord rate " << chord << " m, joint steps' bound " << jointSteps << " m";
  // And still above what its vertices do.
  EXPECT_GE(chord, sampledSpeed(*model, flange, vertices(*model, flange), qa, qb));
}

TEST(ChordBounds, BadIndexOrJointCountIsAnError) {
  const auto model = thesisFree();
  const VectorXd q = VectorXd::Zero(6);
  EXPECT_THROW(chordMotionBound(*model, 99, q, q), arcplan::Error);
  EXPECT_THROW(chordMotionBound(*model, -1, q, q), arcplan::Error);
  EXPECT_THROW(chordMotionBound(*model, 1, VectorXd::Zero(5), q), arcplan::Error);
}

}  // namespace
