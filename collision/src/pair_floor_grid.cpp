// PairFloorGrid (pair_floor_grid.h): floors of a two-joint self pair per cell of the two angles.
#include "pair_floor_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "model_implementation.h"

namespace arcplan::collision::detail {
namespace {

constexpr int kMaxCells = 1024;  // per joint: a long link, fewer and wider cells, lower floors, still bounds
// GJK's distances are exact to about 1e-6 m (docs/collision.md): a floor takes them ten times that smaller.
constexpr double kDistanceSlack = 1e-5;
// The walk along a motion rounds its crossings: a cell it misses is touched by the motion within ~1e-12 rad of a cell
// it visits, over which no distance changes by this much.
constexpr double kWalkSlack = 1e-9;
constexpr double kTurn = 2.0 * M_PI;

int cellsFor(double reach, double cellLoss) {
  return std::clamp(static_cast<int>(std::ceil(kTurn * reach / cellLoss)), 1, kMaxCells);
}

long floorIndex(double x) { return static_cast<long>(std::floor(x)); }

// Angles whose cell index a long holds exactly (a query may pass any value; NaN or 1e300 get no floor).
bool gridded(double angle) { return std::abs(angle) < 1e6; }

int wrapped(long index, int cells) {
  const long r = index % cells;
  return static_cast<int>(r < 0 ? r + cells : r);
}

// The largest float not above x (floors are stored as floats and must stay below what was measured).
float floatBelow(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

PairFloorGrid::PairFloorGrid(std::shared_ptr<const robot::RobotModel> robot, const CollisionModelOptions& options,
                             int jointA, int jointB, std::vector<PartPair> parts, double cellLoss)
    : robot_(std::move(robot)), options_(options), jointA_(jointA), jointB_(jointB), parts_(std::move(parts)) {
  double reachA = 0.0, reachB = 0.0;
  for (const PartPair& pair : parts_) {
    reachA = std::max(reachA, pair.reachA);
    reachB = std::max(reachB, pair.reachB);
  }
  // Each joint's half-cell costs a part pair at most half the loss.
  cellsA_ = cellsFor(reachA, cellLoss);
  cellsB_ = cellsFor(reachB, cellLoss);
  stepA_ = kTurn / cellsA_;
  stepB_ = kTurn / cellsB_;
  floors_ = std::make_unique<std::atomic<float>[]>(static_cast<std::size_t>(cellsA_) * cellsB_);
  for (int k = 0; k < cellsA_ * cellsB_; ++k) floors_[k].store(std::numeric_limits<float>::quiet_NaN());
}

float PairFloorGrid::measure(int a, int b, Eigen::Vector3d* axes) const {
  robot::JointVector q = robot::JointVector::Zero(robot_->dof());
  q[jointA_] = -M_PI + (a + 0.5) * stepA_;
  q[jointB_] = -M_PI + (b + 0.5) * stepB_;
  robot::KinematicsData kinematics(*robot_);
  robot::forwardKinematics(*robot_, q, kinematics);
  double floor = kFloorCap;
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    const PartPair& pair = parts_[p];
    // From the centre to any point of the cell each angle moves at most half a step.
    const double loss = 0.5 * (pair.reachA * stepA_ + pair.reachB * stepB_) + kWalkSlack;
    const Eigen::Isometry3d firstPose = kinematics.linkPoses[pair.firstLink] * pair.first.offset;
    const Eigen::Isometry3d secondPose = kinematics.linkPoses[pair.secondLink] * pair.second.offset;
    const double lower =
        partPairLowerBound(pair.first, firstPose, pair.second, secondPose, options_, floor + loss, axes[p]);
    floor = std::min(floor, lower - loss);
  }
  return floatBelow(floor);
}

double PairFloorGrid::cellFloor(long a, long b, Eigen::Vector3d* axes) const {
  const int i = wrapped(a, cellsA_), j = wrapped(b, cellsB_);
  std::atomic<float>& cell = floors_[static_cast<std::size_t>(i) * cellsB_ + j];
  float floor = cell.load(std::memory_order_relaxed);
  if (std::isnan(floor)) {  // two threads measuring the same cell store the same value
    floor = measure(i, j, axes);
    cell.store(floor, std::memory_order_relaxed);
  }
  return floor;
}

double PairFloorGrid::at(const robot::JointRef& q, Eigen::Vector3d* axes) const {
  if (!gridded(q[jointA_]) || !gridded(q[jointB_])) return -std::numeric_limits<double>::infinity();
  return cellFloor(floorIndex((q[jointA_] + M_PI) / stepA_), floorIndex((q[jointB_] + M_PI) / stepB_), axes);
}

bool PairFloorGrid::keepsAlong(const robot::JointRef& qa, const robot::JointRef& qb, double distance,
                               Eigen::Vector3d* axes) const {
  for (const double angle : {qa[jointA_], qa[jointB_], qb[jointA_], qb[jointB_]})
    if (!gridded(angle)) return false;
  // The cells a straight line crosses, in order (Amanatides & Woo's grid traversal), in cell units.
  const double u0 = (qa[jointA_] + M_PI) / stepA_, v0 = (qa[jointB_] + M_PI) / stepB_;
  const double du = (qb[jointA_] - qa[jointA_]) / stepA_, dv = (qb[jointB_] - qa[jointB_]) / stepB_;
  long a = floorIndex(u0), b = floorIndex(v0);
  const long aEnd = floorIndex(u0 + du), bEnd = floorIndex(v0 + dv);
  const int stepU = aEnd > a ? 1 : -1, stepV = bEnd > b ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  // The motion's fraction at which it next crosses a cell boundary of each joint, and the fraction per cell.
  const double deltaU = du != 0.0 ? 1.0 / std::abs(du) : inf, deltaV = dv != 0.0 ? 1.0 / std::abs(dv) : inf;
  double nextU = du > 0.0 ? (a + 1 - u0) * deltaU : du < 0.0 ? (u0 - a) * deltaU : inf;
  double nextV = dv > 0.0 ? (b + 1 - v0) * deltaV : dv < 0.0 ? (v0 - b) * deltaV : inf;
  // A monotone staircase from the first cell to the last: every crossing is taken once, in the order the
  // fractions give (rounded; see kWalkSlack).
  for (long left = std::abs(aEnd - a) + std::abs(bEnd - b);; --left) {
    if (!(cellFloor(a, b, axes) > distance)) return false;
    if (left == 0) return true;
    if (a != aEnd && (b == bEnd || nextU < nextV)) {
      a += stepU;
      nextU += deltaU;
    } else {
      b += stepV;
      nextV += deltaV;
    }
  }
}

int PairFloorGrid::measuredCells() const {
  int measured = 0;
  for (int k = 0; k < cellsA_ * cellsB_; ++k) measured += !std::isnan(floors_[k].load(std::memory_order_relaxed));
  return measured;
}

double partPairLowerBound(const Part& a, const Eigen::Isometry3d& poseA, const Part& b, const Eigen::Isometry3d& poseB,
                          const CollisionModelOptions& options, double cap, Eigen::Vector3d& axis) {
  const double bound =
      segmentDistance(poseA * a.capsule.start, poseA * a.capsule.end, poseB * b.capsule.start, poseB * b.capsule.end) -
      a.capsule.radius - b.capsule.radius;
  if (bound >= cap) return bound;
  if (options.convexDistance && a.convexGeometry && b.convexGeometry)
    return partsDistance(a, poseA, b, poseB, bound <= 0.0, options, &axis) - kDistanceSlack;
  if (options.hullLayer && a.hullGeometry && b.hullGeometry) return hullGap(a, poseA, b, poseB, options, cap, axis);
  return bound;
}

}  // namespace arcplan::collision::detail
