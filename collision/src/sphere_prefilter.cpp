#include "sphere_prefilter.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace arcplan::collision {
namespace {
std::atomic<bool> prefilterDefault{true};
}  // namespace

void setSpherePrefilterDefault(bool enabled) { prefilterDefault = enabled; }
bool spherePrefilterDefault() { return prefilterDefault; }

}  // namespace arcplan::collision

namespace arcplan::collision::detail {
namespace {

using prefilter::kLanes;

// The float rounding margin. With u = 2^-24 (float unit roundoff), per link row of the chain (sphere_kernel.h):
//   - sin and cos are within 1.1e-7 of the truth (measured, sphere_kernel_chain.h), the angle's rounding
//     to float adds at most 2 pi·u = 4e-7; kTrigError = 2e-6 is taken for both together;
//   - the local rotation c0 + cos·c1 + sin·c2 (c0, c1, c2 from an orthonormal origin rotation, so
//     each of norm <= 1) is off by at most 2·kTrigError + 12u in each entry, the product with the
//     parent's rotation adds 9u per entry; summed over the 9 entries (a bound of the spectral norm)
//     the rotation error grows by at most 2·kTrigError + 64u per moving link, 64u per fixed one;
//   - the translation is off by the parent's (rotation error × |offset|) plus 8u × the chain's
//     reach so far (3 products and 3 sums of terms no larger than that reach);
// a sphere centre c of a link is then off by eT + eR·|c| + 8u·(reach + |c|); the distance from an
// obstacle's frame (one more rotation and translation, a square root) adds 16u × the extent of the
// robot and obstacles; a sum of two radii 2u × their sum. Table entries snapped to 0 or ±1
// (snappedValue) add what they moved: to the rotation error the sum over the entries' coefficients
// (|cos|, |sin| <= 1), to the translation error twice the offsets' (rotated by a parent of norm < 2),
// for the permuted path the origin's entries plus 5·|a − a'| for the axis, and an obstacle's rotation
// moves a world point p by at most its sum × |p| (<= the robot's extent). The kernels require the
// spheres to be clear by twice all that, and the radii are rounded up to float. Rows no joint moves are
// posed in double and rounded to float once (LinkRow::fixedPose): their error, u per entry, stays below
// the bound above, which is kept for them.
constexpr double kUnitRoundoff = 1.0 / 16777216.0;
constexpr double kTrigError = 2e-6;

float roundedUp(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) >= x ? f : std::nextafter(f, INFINITY);
}

// Table entries within kSnap of 0 or ±1 are stored as exactly that, so the kernels skip them
// (sphere_kernel.h); URDF origins written as rpy 1.570796327 leave entries of 2e-10 where the
// rotation has zeros. What snapping moves is added to the error bounds (`snapped`).
constexpr double kSnap = 1e-6;

double snappedValue(double x, double& snapped) {
  for (const double exact : {0.0, 1.0, -1.0}) {
    if (std::abs(x - exact) < kSnap) {
      snapped += std::abs(x - exact);
      return exact;
    }
  }
  return x;
}

// The bounding volume of one obstacle part in its own frame, as a kernel row placed in the world.
// `snapped`: the sum of what snapping moved the rotation's entries (a world point p is then off by
// at most snapped·|p| in the obstacle's frame).
prefilter::ObstacleRow obstacleRow(const Part& part, double& snapped) {
  prefilter::ObstacleRow row{};
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  switch (part.solid.kind) {
    case Solid::Kind::Sphere:
      row.kind = 0;
      row.size[0] = roundedUp(part.solid.radius);
      break;
    case Solid::Kind::Cylinder:
      row.kind = 2;
      row.size[0] = roundedUp(part.solid.radius);
      row.size[1] = roundedUp(part.solid.halfLength);
      break;
    case Solid::Kind::Box:
      row.kind = 1;
      for (int i = 0; i < 3; ++i) row.size[i] = roundedUp(part.solid.halfExtents[i]);
      break;
    default: {
      // A mesh: the box around its vertices (or its capsule) in its own frame.
      Eigen::Vector3d lower = Eigen::Vector3d::Constant(INFINITY), upper = -lower;
      for (const auto& p : part.hullPoints) {
        lower = lower.cwiseMin(p);
        upper = upper.cwiseMax(p);
      }
      if (part.hullPoints.empty()) {
        lower = part.capsule.start.cwiseMin(part.capsule.end).array() - part.capsule.radius;
        upper = part.capsule.start.cwiseMax(part.capsule.end).array() + part.capsule.radius;
      }
      row.kind = 1;
      centre = (lower + upper) / 2.0;
      for (int i = 0; i < 3; ++i) row.size[i] = roundedUp((upper[i] - lower[i]) / 2.0 + 1e-7);
    }
  }
  // local = R^T (p - t) - centre
  const Eigen::Matrix3d toLocal = part.offset.linear().transpose();
  snapped = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) row.rotation[3 * i + j] = static_cast<float>(snappedValue(toLocal(i, j), snapped));
  row.aligned = 1;
  for (int i = 0; i < 9; ++i) row.aligned = row.aligned && row.rotation[i] == (i % 4 == 0 ? 1.0f : 0.0f);
  const Eigen::Vector3d translation = -(toLocal * part.offset.translation()) - centre;
  for (int i = 0; i < 3; ++i) row.translation[i] = static_cast<float>(translation[i]);
  return row;
}

// Distance of the world point p from the row's volume (what the kernels' obstacleDistance computes in float),
// in double; the rotation snapping (`snapped`, obstacleRow) taken off as it may move p in the obstacle's frame.
double rowDistance(const prefilter::ObstacleRow& row, double snapped, const Eigen::Vector3d& p) {
  Eigen::Vector3d local;
  for (int i = 0; i < 3; ++i) {
    local[i] = row.rotation[3 * i] * p.x() + row.rotation[3 * i + 1] * p.y() + row.rotation[3 * i + 2] * p.z() +
               row.translation[i];
  }
  double distance = 0.0;
  if (row.kind == 0) {
    distance = local.norm() - row.size[0];
  } else if (row.kind == 1) {
    distance = (local.cwiseAbs() - Eigen::Vector3d(row.size[0], row.size[1], row.size[2])).cwiseMax(0.0).norm();
  } else {
    distance = std::hypot(std::max(std::hypot(local.x(), local.y()) - row.size[0], 0.0),
                          std::max(std::abs(local.z()) - row.size[1], 0.0));
  }
  return distance - snapped * p.norm();
}

// Whether the snapped origin rotation is a signed permutation and the joint axis a coordinate axis
// (sphere_tables.h, LinkRow::permuted); the snapping this takes is added to `snapped`.
void describePermutation(const robot::Link& link, prefilter::LinkRow& row, double& snapped) {
  const Eigen::Matrix3d origin = link.originInParent.linear();
  double moved = 0.0;
  row.permuted = 1;
  for (int j = 0; j < 3; ++j) {
    int nonzero = 0;
    for (int i = 0; i < 3; ++i) {
      const double x = snappedValue(origin(i, j), moved);
      if (x == 0.0) continue;
      if (std::abs(x) != 1.0) row.permuted = 0;
      row.column[j] = i;
      row.sign[j] = static_cast<float>(x);
      ++nonzero;
    }
    if (nonzero != 1) row.permuted = 0;
  }
  row.axis = -1;
  row.axisSign = 1.0f;
  if (link.joint >= 0) {
    const Eigen::Vector3d a = link.axis.normalized();
    for (int k = 0; k < 3; ++k) {
      if (std::abs(std::abs(a[k]) - 1.0) < kSnap) {
        row.axis = k;
        row.axisSign = a[k] < 0.0 ? -1.0f : 1.0f;
        // Rot(a, q) = I + sin q·[a]× + (1 − cos q)·[a]×² moves by at most 5·|a − a'| with the axis.
        moved += 5.0 * (a - static_cast<double>(row.axisSign) * Eigen::Vector3d::Unit(k)).norm();
      }
    }
    if (row.axis < 0) row.permuted = 0;
  }
  // One of the two paths computes the rotation: the bound takes the larger of their snapping.
  if (row.permuted) snapped = std::max(snapped, moved);
}

// The row and, in `snapped`, the sum over the 9 rotation entries of what snapping moved their
// coefficients (a bound of the local rotation's extra error for any q: |cos|, |sin| <= 1) and the
// sum of what it moved the translation's components.
prefilter::LinkRow linkRow(const robot::Link& link, int parentRow, double& snappedRotation,
                           double& snappedTranslation) {
  prefilter::LinkRow row{};
  row.parent = parentRow;
  row.joint = link.joint;
  const Eigen::Matrix3d origin = link.originInParent.linear();
  Eigen::Matrix3d c0 = origin, c1 = Eigen::Matrix3d::Zero(), c2 = Eigen::Matrix3d::Zero();
  if (link.joint >= 0) {
    const Eigen::Vector3d a = link.axis.normalized();
    Eigen::Matrix3d cross;
    cross << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
    c0 = origin * a * a.transpose();
    c1 = origin - c0;
    c2 = origin * cross;
  }
  snappedRotation = snappedTranslation = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      row.c0[3 * i + j] = static_cast<float>(snappedValue(c0(i, j), snappedRotation));
      row.c1[3 * i + j] = static_cast<float>(snappedValue(c1(i, j), snappedRotation));
      row.c2[3 * i + j] = static_cast<float>(snappedValue(c2(i, j), snappedRotation));
    }
    row.t[i] = static_cast<float>(snappedValue(link.originInParent.translation()[i], snappedTranslation));
  }
  describePermutation(link, row, snappedRotation);
  row.zero = row.constant = 0;
  for (int i = 0; i < 9; ++i) {
    if (row.c1[i] == 0.0f && row.c2[i] == 0.0f) row.constant |= 1u << i;
    if (row.c0[i] == 0.0f && row.c1[i] == 0.0f && row.c2[i] == 0.0f) row.zero |= 1u << i;
  }
  return row;
}

}  // namespace

SpherePrefilter::SpherePrefilter(const robot::RobotModel& robot, const ModelImplementation& impl,
                                 const std::vector<std::string>& linkNames)
    : spheres_(robotSphereModel(impl, linkNames)) {
  // Chain rows: links with geometry and their ancestors, parents first.
  const auto& links = robot.links();
  std::vector<bool> needed(links.size(), false);
  for (const int link : impl.linkCapsuleLink)
    for (int l = link; l >= 0 && !needed[l]; l = links[l].parent) needed[l] = true;
  std::vector<int> rowOf(links.size(), -1);
  std::vector<double> eR, eT, reach;
  std::vector<Eigen::Isometry3d> worldPose;  // per row: its world pose where no joint moves it (fixedPose)
  for (std::size_t l = 0; l < links.size(); ++l) {
    if (!needed[l]) continue;
    const int parent = links[l].parent < 0 ? -1 : rowOf[links[l].parent];
    rowOf[l] = static_cast<int>(links_.size());
    double snappedRotation = 0.0, snappedTranslation = 0.0;
    links_.push_back(linkRow(links[l], parent, snappedRotation, snappedTranslation));
    prefilter::LinkRow& row = links_.back();
    row.fixedPose = links[l].joint < 0 && (parent < 0 || links_[parent].fixedPose);
    worldPose.push_back(parent < 0 ? links[l].originInParent : worldPose[parent] * links[l].originInParent);
    if (row.fixedPose) {
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) row.fixedR[3 * i + j] = static_cast<float>(worldPose.back().linear()(i, j));
        row.fixedT[i] = static_cast<float>(worldPose.back().translation()[i]);
      }
    }
    const double offset = links[l].originInParent.translation().norm();
    const double parentR = parent < 0 ? 0.0 : eR[parent], parentT = parent < 0 ? 0.0 : eT[parent];
    reach.push_back((parent < 0 ? 0.0 : reach[parent]) + offset);
    eR.push_back(parentR + (links[l].joint >= 0 ? 2.0 * kTrigError : 0.0) + 64.0 * kUnitRoundoff + snappedRotation);
    // The snapped translation is rotated by the parent's rotation, of norm <= 1 + parentR < 2.
    eT.push_back(parentT + parentR * offset + 8.0 * kUnitRoundoff * reach.back() + 2.0 * snappedTranslation);
  }
  // Bodies and their fine spheres.
  double centreError = 0.0, robotExtent = 0.0, radiusSum = 0.0;
  for (std::size_t b = 0; b < spheres_->size(); ++b) {
    const BodySpheres& body = (*spheres_)[b];
    const int row = rowOf[impl.linkCapsuleLink[b]];
    prefilter::BodyRow bodyRow{};
    bodyRow.link = row;
    for (int i = 0; i < 3; ++i) bodyRow.coarse[i] = static_cast<float>(body.coarse.centre[i]);
    bodyRow.coarse[3] = roundedUp(body.coarse.radius);
    bodyRow.fineBegin = static_cast<int>(fineX_.size());
    bodyRow.fineCount = static_cast<int>(body.fine.size());
    bodyRow.groupBegin = static_cast<int>(groups_.size());
    bodyRow.groupCount = static_cast<int>(body.groups.size());
    std::vector<Sphere> all = body.fine;
    all.push_back(body.coarse);
    for (const auto& group : body.groups) {
      prefilter::GroupRow groupRow{};
      for (int i = 0; i < 3; ++i) groupRow.ball[i] = static_cast<float>(group.bound.centre[i]);
      groupRow.ball[3] = roundedUp(group.bound.radius);
      groupRow.fineBegin = bodyRow.fineBegin + group.begin;
      groupRow.fineCount = group.count;
      groups_.push_back(groupRow);
      all.push_back(group.bound);
    }
    for (const auto& s : all) {
      const double c = s.centre.norm();
      centreError = std::max(centreError, eT[row] + eR[row] * c + 8.0 * kUnitRoundoff * (reach[row] + c));
      robotExtent = std::max(robotExtent, reach[row] + c + s.radius);
      radiusSum = std::max(radiusSum, 2.0 * s.radius);
    }
    for (const auto& s : body.fine) {
      fineX_.push_back(static_cast<float>(s.centre.x()));
      fineY_.push_back(static_cast<float>(s.centre.y()));
      fineZ_.push_back(static_cast<float>(s.centre.z()));
      fineR_.push_back(roundedUp(s.radius));
    }
    usable_ = usable_ || !body.fine.empty();
    bodies_.push_back(bodyRow);
  }
  // Obstacles: the bounding volume of every part, and per body the parts of its non-allowed obstacles.
  double obstacleExtent = 0.0, obstacleSnapped = 0.0;
  std::vector<double> partSnapped;
  for (const Part& part : impl.obstacleParts) {
    double snapped = 0.0;
    obstacles_.push_back(obstacleRow(part, snapped));
    partSnapped.push_back(snapped);
    obstacleSnapped = std::max(obstacleSnapped, snapped);
    const auto& row = obstacles_.back();
    obstacleExtent =
        std::max(obstacleExtent,
                 part.offset.translation().norm() + Eigen::Vector3f(row.size[0], row.size[1], row.size[2]).norm() +
                     Eigen::Vector3f(row.translation[0], row.translation[1], row.translation[2]).norm());
  }
  // A rigid pair apart (measured once, ModelImplementation::PairGroup) can never touch: not in the tables.
  for (std::size_t k = 0; k < impl.selfGroups.size(); ++k) {
    const auto& group = impl.selfGroups[k];
    const bool never = group.rigid && !group.rigidCollides;
    kernelPairs_.push_back(never ? -1 : static_cast<int>(selfGroupsOfPairs_.size()));
    if (never) continue;
    selfGroupsOfPairs_.push_back(static_cast<int>(k));
    // The kernel tests each fine sphere of a pair's first body against the second's coarse sphere before any of the
    // second's fine ones: the body with more fine spheres goes first, so that the small coarse sphere of the other
    // (a wrist, the shoulder) dismisses most of them. Either order is conservative and, but for float rounding,
    // decides the same: a sphere clear of a coarse sphere is clear of the fine ones inside it.
    const bool swap = bodies_[group.secondBody].fineCount > bodies_[group.firstBody].fineCount;
    selfPairs_.insert(selfPairs_.end(),
                      {swap ? group.secondBody : group.firstBody, swap ? group.firstBody : group.secondBody});
  }
  if (links_.size() > static_cast<std::size_t>(prefilter::kMaxLinks) || robot.dof() > prefilter::kMaxJoints ||
      bodies_.size() > static_cast<std::size_t>(prefilter::kMaxBodies) ||
      fineX_.size() > static_cast<std::size_t>(prefilter::kMaxFineSpheres) ||
      groups_.size() > static_cast<std::size_t>(prefilter::kMaxGroups)) {
    usable_ = false;
  }

  centreErrorBound_ = centreError;
  const double rounding = 16.0 * kUnitRoundoff * (robotExtent + obstacleExtent) + 2.0 * kUnitRoundoff * radiusSum +
                          obstacleSnapped * robotExtent;
  tables_.margin = roundedUp(2.0 * (2.0 * centreError + rounding));
  // Per body the parts of its non-allowed obstacles; a body no joint moves measures them once (BodyRow::fixedGap).
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    prefilter::BodyRow& body = bodies_[b];
    body.obstacleBegin = static_cast<int>(obstacleIndex_.size());
    // The fine spheres' gap to an obstacle part, for a body on a fixed row (the same in every state).
    const auto fineGap = [&](int part) {
      double gap = INFINITY;
      for (const Sphere& s : (*spheres_)[b].fine) {
        gap = std::min(gap, rowDistance(obstacles_[part], partSnapped[part], worldPose[body.link] * s.centre) -
                                static_cast<double>(roundedUp(s.radius)));
      }
      return gap;
    };
    double fixedGap = prefilter::kFarGap;
    for (const auto& group : impl.obstacleGroups) {
      if (group.firstBody != static_cast<int>(b)) continue;
      for (const int part : group.obstacleParts) {
        const double gap = links_[body.link].fixedPose ? fineGap(part) : -INFINITY;
        if (gap > tables_.margin) {
          fixedGap = std::min(fixedGap, gap);
        } else {
          obstacleIndex_.push_back(part);
        }
      }
    }
    body.obstacleCount = static_cast<int>(obstacleIndex_.size()) - body.obstacleBegin;
    // Rounded down to float: still a lower bound.
    const float rounded = static_cast<float>(fixedGap);
    body.fixedGap = static_cast<double>(rounded) <= fixedGap ? rounded : std::nextafter(rounded, -INFINITY);
  }
  tables_.dof = robot.dof();
  tables_.linkCount = static_cast<int>(links_.size());
  tables_.bodyCount = static_cast<int>(bodies_.size());
  tables_.obstacleCount = static_cast<int>(obstacles_.size());
  tables_.selfPairCount = static_cast<int>(selfPairs_.size() / 2);
  tables_.links = links_.data();
  tables_.bodies = bodies_.data();
  tables_.fineX = fineX_.data();
  tables_.fineY = fineY_.data();
  tables_.fineZ = fineZ_.data();
  tables_.fineR = fineR_.data();
  tables_.groups = groups_.data();
  tables_.obstacles = obstacles_.data();
  tables_.obstacleIndex = obstacleIndex_.data();
  tables_.selfPairs = selfPairs_.data();
#ifdef ARCPLAN_HAVE_AVX2_KERNEL
  __builtin_cpu_init();
  avx2_ = __builtin_cpu_supports("avx2");
#endif
}

int SpherePrefilter::gapPairOfGroup(const ModelImplementation& impl, std::size_t k) const {
  const std::size_t obstacleGroups = impl.obstacleGroups.size();
  if (k < obstacleGroups) return impl.obstacleGroups[k].firstBody;
  const int pair = kernelPairs_[k - obstacleGroups];
  return pair < 0 ? -1 : tables_.bodyCount + pair;
}

void SpherePrefilter::prepare(SphereWorkspace& workspace) const {
  workspace.q.assign(static_cast<std::size_t>(tables_.dof) * kLanes, 0.0f);
  workspace.laneStates.assign(static_cast<std::size_t>(tables_.dof) * kLanes, 0.0);
  workspace.gaps.assign(static_cast<std::size_t>(pairCount()) * kLanes, 0.0f);
  workspace.enough.assign(static_cast<std::size_t>(pairCount()), 0.0f);
}

void SpherePrefilter::loadLanes(SphereWorkspace& workspace, const double* states, std::ptrdiff_t stride,
                                int lanes) const {
  float* q = workspace.q.data();
#ifdef ARCPLAN_HAVE_AVX2_KERNEL
  const bool loaded = avx2_ ? prefilter::loadLanesAvx2(states, stride, tables_.dof, lanes, q)
                            : prefilter::loadLanesPortable(states, stride, tables_.dof, lanes, q);
#else
  const bool loaded = prefilter::loadLanesPortable(states, stride, tables_.dof, lanes, q);
#endif
  if (loaded) return;
  // An angle beyond the kernels' range: each state reduced on its own.
  for (int lane = 0; lane < kLanes; ++lane) loadLane(workspace, lane, states + (lane < lanes ? lane : 0) * stride);
}

std::uint32_t SpherePrefilter::freeLanes(SphereWorkspace& workspace, int lanes) const {
  if (!usable_) return 0;
  // Unused lanes repeat the first state, so the kernels never see garbage.
  for (int j = 0; j < tables_.dof; ++j) {
    for (int lane = lanes; lane < kLanes; ++lane) workspace.q[j * kLanes + lane] = workspace.q[j * kLanes];
  }
#ifdef ARCPLAN_HAVE_AVX2_KERNEL
  if (avx2_ && lanes > 1) return prefilter::freeLanesAvx2(tables_, workspace.q.data(), lanes);
#endif
  return prefilter::freeLanesPortable(tables_, workspace.q.data(), lanes);
}

void SpherePrefilter::gaps(SphereWorkspace& workspace) const {
#ifdef ARCPLAN_HAVE_AVX2_KERNEL
  if (avx2_) return prefilter::gapsAvx2(tables_, workspace.q.data(), workspace.enough.data(), workspace.gaps.data());
#endif
  prefilter::gapsPortable(tables_, workspace.q.data(), workspace.enough.data(), workspace.gaps.data());
}

void collisionGaps(const SpherePrefilter& prefilter, SphereWorkspace& workspace) {
  std::fill(workspace.enough.begin(), workspace.enough.begin() + prefilter.pairCount(),
            static_cast<float>(prefilter.margin()));
  prefilter.gaps(workspace);
}

bool sphereFree(const SpherePrefilter& prefilter, SphereWorkspace& workspace, const robot::JointRef& q) {
  if (q.size() != prefilter.dof()) return false;
  prefilter.loadLane(workspace, 0, q.data());
  return prefilter.freeLanes(workspace, 1) != 0;
}

}  // namespace arcplan::collision::detail
