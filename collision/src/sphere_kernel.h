#pragma once
// The sphere prefilter's kernels, written once for a lane type V and compiled twice: by
// sphere_kernel_portable.cpp (plain floats, any CPU) and sphere_kernel_avx2.cpp (8 AVX2 lanes).
// The including file defines, before including this header, in the same namespace:
//   V (with V::kLanes and V::Mask); broadcast<V>(float), load<V>(const float*), store(float*, V);
//   V + V, V - V, V * V, -V; squareRoot, minimum (a < b ? a : b), maximum (a > b ? a : b),
//   absolute, roundNearest (ties to even), floorOf; greater, greaterEqual, equal -> Mask;
//   Mask | Mask, Mask & Mask, ~Mask, allLanes<V>(), select(Mask, V a, V b) (a where set), allOf(Mask), bits(Mask).
// Both definitions are IEEE single precision without fused multiply-adds (the kernels are built
// with -ffp-contract=off) and every operation below is done in the same order, so both paths
// compute the same bits and take the same decisions. Everything is in an anonymous namespace:
// each translation unit keeps its own copy, nothing is shared between them (see sphere_tables.h).
#include "sphere_kernel_chain.h"

namespace arcplan::collision::detail::prefilter {
namespace {

// The obstacle tests are called from several loops of each kernel; left to itself the compiler stopped
// inlining them once the group loops came in, and the calls cost 18 % of a free-space batch.
#if defined(__GNUC__)
#define ARCPLAN_KERNEL_INLINE inline __attribute__((always_inline))
#else
#define ARCPLAN_KERNEL_INLINE inline
#endif

// The world point p in the obstacle's frame; an axis-aligned obstacle (rotation exactly the
// identity, the usual table) costs three additions, the same bits as the full product.
template <class V>
ARCPLAN_KERNEL_INLINE void toObstacleFrame(const ObstacleRow& o, const V* p, V* l) {
  if (o.aligned) {
    for (int i = 0; i < 3; ++i) l[i] = p[i] + broadcast<V>(o.translation[i]);
    return;
  }
  for (int i = 0; i < 3; ++i) {
    l[i] = ((broadcast<V>(o.rotation[3 * i]) * p[0] + broadcast<V>(o.rotation[3 * i + 1]) * p[1]) +
            broadcast<V>(o.rotation[3 * i + 2]) * p[2]) +
           broadcast<V>(o.translation[i]);
  }
}

// Distance of the world point p from the obstacle's volume (<= 0 inside a sphere, 0 inside a box or cylinder).
template <class V>
ARCPLAN_KERNEL_INLINE V obstacleDistance(const ObstacleRow& o, const V* p) {
  V l[3];
  toObstacleFrame(o, p, l);
  const V zero = broadcast<V>(0.0f);
  if (o.kind == 0) return squareRoot((l[0] * l[0] + l[1] * l[1]) + l[2] * l[2]) - broadcast<V>(o.size[0]);
  if (o.kind == 1) {
    V d[3];
    for (int i = 0; i < 3; ++i) d[i] = maximum(absolute(l[i]) - broadcast<V>(o.size[i]), zero);
    return squareRoot((d[0] * d[0] + d[1] * d[1]) + d[2] * d[2]);
  }
  const V radial = maximum(squareRoot(l[0] * l[0] + l[1] * l[1]) - broadcast<V>(o.size[0]), zero);
  const V axial = maximum(absolute(l[2]) - broadcast<V>(o.size[1]), zero);
  return squareRoot(radial * radial + axial * axial);
}

// Whether the ball (centre p, radius + margin = reach) is clear of the obstacle's volume, compared
// squared where no square root is needed (the same decision in every lane type).
template <class V>
ARCPLAN_KERNEL_INLINE typename V::Mask obstacleClear(const ObstacleRow& o, const V* p, float reach) {
  V l[3];
  toObstacleFrame(o, p, l);
  const V zero = broadcast<V>(0.0f);
  if (o.kind == 0) {
    const float total = o.size[0] + reach;
    return greater((l[0] * l[0] + l[1] * l[1]) + l[2] * l[2], broadcast<V>(total * total));
  }
  V d[3];
  if (o.kind == 1) {
    for (int i = 0; i < 3; ++i) d[i] = maximum(absolute(l[i]) - broadcast<V>(o.size[i]), zero);
  } else {
    d[0] = maximum(squareRoot(l[0] * l[0] + l[1] * l[1]) - broadcast<V>(o.size[0]), zero);
    d[1] = maximum(absolute(l[2]) - broadcast<V>(o.size[1]), zero);
    d[2] = zero;
  }
  return greater((d[0] * d[0] + d[1] * d[1]) + d[2] * d[2], broadcast<V>(reach * reach));
}

template <class V>
V squaredCentreDistance(const V* a, const V* b) {
  const V dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return (dx * dx + dy * dy) + dz * dz;
}

template <class V>
V centreDistance(const V* a, const V* b) {
  const V dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return squareRoot((dx * dx + dy * dy) + dz * dz);
}

// The world centres of the spheres, computed once per kernel call when first needed: a body's group
// balls together, a group's fine spheres together.
template <class V>
struct Placement {
  // A constructor, so that `fine` and `group` are not zero-filled on every call (54 KB for AVX2).
  Placement(const Tables& t, const Pose<V>* p) : tables(t), poses(p) {}
  const Tables& tables;
  const Pose<V>* poses;
  V fine[kMaxFineSpheres][3];
  V group[kMaxGroups][3];
  std::uint64_t groupsPlaced = 0;                         // bit b: body b's group balls are in `group`
  std::uint64_t finePlaced[(kMaxGroups + 63) / 64] = {};  // bit g: group g's fine spheres are in `fine`

  const V (*groupsOf(const BodyRow& body, int b))[3] {
    if (!((groupsPlaced >> b) & 1u)) {
      for (int g = body.groupBegin; g < body.groupBegin + body.groupCount; ++g) {
        const float* ball = tables.groups[g].ball;
        place(poses[body.link], ball[0], ball[1], ball[2], group[g]);
      }
      groupsPlaced |= std::uint64_t{1} << b;
    }
    return group + body.groupBegin;
  }

  const V (*fineOfGroup(const BodyRow& body, int g))[3] {
    std::uint64_t& word = finePlaced[g / 64];
    const GroupRow& row = tables.groups[g];
    if (!((word >> (g % 64)) & 1u)) {
      for (int k = row.fineBegin; k < row.fineBegin + row.fineCount; ++k)
        place(poses[body.link], tables.fineX[k], tables.fineY[k], tables.fineZ[k], fine[k]);
      word |= std::uint64_t{1} << (g % 64);
    }
    return fine + row.fineBegin;
  }

  const V (*fineOf(const BodyRow& body))[3] {
    for (int g = body.groupBegin; g < body.groupBegin + body.groupCount; ++g) fineOfGroup(body, g);
    return fine + body.fineBegin;
  }
};

// A lane is decided by its own numbers only: a body is clear of an obstacle when each of its groups
// is clear by its ball (a body of one group: by its coarse sphere) or by each of the group's fine
// spheres; a self pair when the coarse spheres are clear, or each group of the first body is clear
// of the second's coarse sphere by its ball or by each of its fine spheres, which are clear of that
// coarse sphere or of all the second's fine spheres. Which lanes reach the finer tests depends on the
// batch, but not a lane's decision, so one state gets the same answer alone or in any batch. The
// group balls are all tested before the one branch that asks whether any lane needs more: a branch
// per group, taken about half the time on an arm's middle group, cost more in mispredictions than
// the tests it saved.
template <class V>
std::uint32_t freeLanes(const Tables& tables, const float* q) {
  using Mask = typename V::Mask;
  Pose<V> poses[kMaxLinks];
  forwardKinematics(tables, q, poses);
  Placement<V> placement(tables, poses);
  V coarse[kMaxBodies][3];
  for (int b = 0; b < tables.bodyCount; ++b) {
    const BodyRow& body = tables.bodies[b];
    place(poses[body.link], body.coarse[0], body.coarse[1], body.coarse[2], coarse[b]);
  }
  Mask groupClear[kMaxGroups];
  Mask unsure = ~allLanes<V>();
  for (int b = 0; b < tables.bodyCount; ++b) {
    const BodyRow& body = tables.bodies[b];
    const V(*balls)[3] = body.groupCount > 1 ? placement.groupsOf(body, b) : coarse + b;
    for (int k = 0; k < body.obstacleCount; ++k) {
      const ObstacleRow& o = tables.obstacles[tables.obstacleIndex[body.obstacleBegin + k]];
      Mask clear = allLanes<V>();
      for (int g = 0; g < body.groupCount; ++g) {
        groupClear[g] = obstacleClear(o, balls[g], tables.groups[body.groupBegin + g].ball[3] + tables.margin);
        clear = clear & groupClear[g];
      }
      if (allOf(clear | unsure)) continue;
      for (int g = 0; g < body.groupCount; ++g) {
        if (allOf(groupClear[g] | unsure)) continue;
        const GroupRow& group = tables.groups[body.groupBegin + g];
        const V(*fine)[3] = placement.fineOfGroup(body, body.groupBegin + g);
        Mask fineClear = allLanes<V>();
        for (int f = 0; f < group.fineCount; ++f) {  // no early exit: a mispredicted branch costs more
          fineClear = fineClear & obstacleClear(o, fine[f], tables.fineR[group.fineBegin + f] + tables.margin);
        }
        unsure = unsure | ~(groupClear[g] | fineClear);
      }
      if (allOf(unsure)) return 0;
    }
  }
  for (int p = 0; p < tables.selfPairCount; ++p) {
    const int ia = tables.selfPairs[2 * p], ib = tables.selfPairs[2 * p + 1];
    const BodyRow &a = tables.bodies[ia], &b = tables.bodies[ib];
    const float coarseReach = (a.coarse[3] + b.coarse[3]) + tables.margin;
    const Mask coarseClear =
        greater(squaredCentreDistance(coarse[ia], coarse[ib]), broadcast<V>(coarseReach * coarseReach));
    Mask settled = coarseClear | unsure;
    if (allOf(settled)) continue;
    Mask clear = allLanes<V>();
    if (a.groupCount > 1) {
      const V(*ballsA)[3] = placement.groupsOf(a, ia);
      for (int g = 0; g < a.groupCount; ++g) {
        const float groupReach = (tables.groups[a.groupBegin + g].ball[3] + b.coarse[3]) + tables.margin;
        groupClear[g] = greater(squaredCentreDistance(ballsA[g], coarse[ib]), broadcast<V>(groupReach * groupReach));
        clear = clear & groupClear[g];
      }
      if (allOf(clear | settled)) continue;
    } else {
      groupClear[0] = coarseClear;
    }
    for (int g = 0; g < a.groupCount; ++g) {
      if (allOf(groupClear[g] | settled)) continue;
      const GroupRow& group = tables.groups[a.groupBegin + g];
      const V(*fineA)[3] = placement.fineOfGroup(a, a.groupBegin + g);
      Mask fineClear = allLanes<V>();
      for (int i = 0; i < group.fineCount; ++i) {
        const float radiusA = tables.fineR[group.fineBegin + i];
        const float reachB = (radiusA + b.coarse[3]) + tables.margin;
        const Mask clearOfB = greater(squaredCentreDistance(fineA[i], coarse[ib]), broadcast<V>(reachB * reachB));
        if (allOf(clearOfB | settled | groupClear[g])) continue;
        const V(*fineB)[3] = placement.fineOf(b);
        Mask sphereClear = allLanes<V>();
        for (int j = 0; j < b.fineCount; ++j) {
          const float reach = (radiusA + tables.fineR[b.fineBegin + j]) + tables.margin;
          sphereClear = sphereClear & greater(squaredCentreDistance(fineA[i], fineB[j]), broadcast<V>(reach * reach));
        }
        fineClear = fineClear & (clearOfB | sphereClear);
      }
      unsure = unsure | ~(coarseClear | groupClear[g] | fineClear);
    }
    if (allOf(unsure)) return 0;
  }
  return bits(~unsure);
}

template <class V>
void gaps(const Tables& tables, const float* q, const float* enough, float* out) {
  Pose<V> poses[kMaxLinks];
  forwardKinematics(tables, q, poses);
  Placement<V> placement(tables, poses);
  const V margin = broadcast<V>(tables.margin);
  V coarse[kMaxBodies][3];
  for (int b = 0; b < tables.bodyCount; ++b) {
    const BodyRow& body = tables.bodies[b];
    place(poses[body.link], body.coarse[0], body.coarse[1], body.coarse[2], coarse[b]);
  }
  for (int b = 0; b < tables.bodyCount; ++b) {
    const BodyRow& body = tables.bodies[b];
    V best = broadcast<V>(body.fixedGap);
    for (int k = 0; k < body.obstacleCount; ++k) {
      const ObstacleRow& o = tables.obstacles[tables.obstacleIndex[body.obstacleBegin + k]];
      const V coarseGap = obstacleDistance(o, coarse[b]) - broadcast<V>(body.coarse[3]);
      if (allOf(greaterEqual(coarseGap, broadcast<V>(enough[b])))) {
        best = minimum(best, coarseGap);
        continue;
      }
      // Group by group: a group whose ball reaches `enough` keeps its ball's bound.
      const V(*balls)[3] = body.groupCount > 1 ? placement.groupsOf(body, b) : nullptr;
      V fineGap = broadcast<V>(kFarGap);
      for (int g = 0; g < body.groupCount; ++g) {
        const GroupRow& group = tables.groups[body.groupBegin + g];
        V groupGap = coarseGap;  // a body of one group: its ball is the coarse sphere
        if (balls != nullptr) {
          groupGap = obstacleDistance(o, balls[g]) - broadcast<V>(group.ball[3]);
          if (allOf(greaterEqual(groupGap, broadcast<V>(enough[b])))) {
            fineGap = minimum(fineGap, groupGap);
            continue;
          }
        }
        const V(*fine)[3] = placement.fineOfGroup(body, body.groupBegin + g);
        V groupFine = broadcast<V>(kFarGap);
        for (int f = 0; f < group.fineCount; ++f) {
          groupFine =
              minimum(groupFine, obstacleDistance(o, fine[f]) - broadcast<V>(tables.fineR[group.fineBegin + f]));
        }
        fineGap = minimum(fineGap, maximum(groupGap, groupFine));
      }
      best = minimum(best, maximum(coarseGap, fineGap));
    }
    store(out + b * kLanes, best - margin);
  }
  for (int p = 0; p < tables.selfPairCount; ++p) {
    const int ia = tables.selfPairs[2 * p], ib = tables.selfPairs[2 * p + 1];
    const BodyRow &a = tables.bodies[ia], &b = tables.bodies[ib];
    V best = centreDistance(coarse[ia], coarse[ib]) - broadcast<V>(a.coarse[3] + b.coarse[3]);
    const int pair = tables.bodyCount + p;
    if (!allOf(greaterEqual(best, broadcast<V>(enough[pair])))) {
      // Group against group: a pair of groups whose balls reach `enough` keeps their bound.
      const V(*ballsA)[3] = a.groupCount > 1 ? placement.groupsOf(a, ia) : coarse + ia;
      const V(*ballsB)[3] = b.groupCount > 1 ? placement.groupsOf(b, ib) : coarse + ib;
      V fineGap = broadcast<V>(kFarGap);
      for (int g = 0; g < a.groupCount; ++g) {
        const GroupRow& groupA = tables.groups[a.groupBegin + g];
        for (int h = 0; h < b.groupCount; ++h) {
          const GroupRow& groupB = tables.groups[b.groupBegin + h];
          const V groupGap = centreDistance(ballsA[g], ballsB[h]) - broadcast<V>(groupA.ball[3] + groupB.ball[3]);
          if (allOf(greaterEqual(groupGap, broadcast<V>(enough[pair])))) {
            fineGap = minimum(fineGap, groupGap);
            continue;
          }
          const V(*fineA)[3] = placement.fineOfGroup(a, a.groupBegin + g);
          const V(*fineB)[3] = placement.fineOfGroup(b, b.groupBegin + h);
          V groupFine = broadcast<V>(kFarGap);
          for (int i = 0; i < groupA.fineCount; ++i) {
            const float radiusA = tables.fineR[groupA.fineBegin + i];
            for (int j = 0; j < groupB.fineCount; ++j) {
              groupFine = minimum(groupFine, centreDistance(fineA[i], fineB[j]) -
                                                 broadcast<V>(radiusA + tables.fineR[groupB.fineBegin + j]));
            }
          }
          fineGap = minimum(fineGap, maximum(groupGap, groupFine));
        }
      }
      best = maximum(best, fineGap);
    }
    store(out + pair * kLanes, best - margin);
  }
}

}  // namespace
}  // namespace arcplan::collision::detail::prefilter
