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

constexpr float kFar = 1e30f;  // "no pair measured": larger than any distance

// The world point p in the obstacle's frame; an axis-aligned obstacle (rotation exactly the
// identity, the usual table) costs three additions, the same bits as the full product.
template <class V>
void toObstacleFrame(const ObstacleRow& o, const V* p, V* l) {
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
V obstacleDistance(const ObstacleRow& o, const V* p) {
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
typename V::Mask obstacleClear(const ObstacleRow& o, const V* p, float reach) {
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

// The world centres of the spheres, computed once per kernel call and body when first needed.
template <class V>
struct Placement {
  // A constructor, so that `fine` is not zero-filled on every call (36 KB for AVX2).
  Placement(const Tables& t, const Pose<V>* p) : tables(t), poses(p) {}
  const Tables& tables;
  const Pose<V>* poses;
  V fine[kMaxFineSpheres][3];
  std::uint64_t placed = 0;  // bit b: body b's fine spheres are in `fine`

  const V (*fineOf(const BodyRow& body, int b))[3] {
    if (!((placed >> b) & 1u)) {
      for (int f = 0; f < body.fineCount; ++f) {
        const int k = body.fineBegin + f;
        place(poses[body.link], tables.fineX[k], tables.fineY[k], tables.fineZ[k], fine[k]);
      }
      placed |= std::uint64_t{1} << b;
    }
    return fine + body.fineBegin;
  }
};

// A lane is decided by its own numbers only: a pair is clear by the coarse spheres, or else each
// fine sphere of the first body is clear of the second's coarse sphere (self pairs) or of all its
// fine spheres. Which lanes reach the finer tests depends on the batch, but not a lane's decision, so
// one state gets the same answer alone or in any batch.
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
  Mask unsure = ~allLanes<V>();
  for (int b = 0; b < tables.bodyCount; ++b) {
    const BodyRow& body = tables.bodies[b];
    for (int k = 0; k < body.obstacleCount; ++k) {
      const ObstacleRow& o = tables.obstacles[tables.obstacleIndex[body.obstacleBegin + k]];
      const Mask coarseClear = obstacleClear(o, coarse[b], body.coarse[3] + tables.margin);
      if (allOf(coarseClear | unsure)) continue;
      const V(*fine)[3] = placement.fineOf(body, b);
      Mask fineClear = allLanes<V>();
      for (int f = 0; f < body.fineCount; ++f) {  // no early exit: a mispredicted branch costs more
        fineClear = fineClear & obstacleClear(o, fine[f], tables.fineR[body.fineBegin + f] + tables.margin);
      }
      unsure = unsure | ~(coarseClear | fineClear);
      if (allOf(unsure)) return 0;
    }
  }
  for (int p = 0; p < tables.selfPairCount; ++p) {
    const int ia = tables.selfPairs[2 * p], ib = tables.selfPairs[2 * p + 1];
    const BodyRow &a = tables.bodies[ia], &b = tables.bodies[ib];
    const float coarseReach = (a.coarse[3] + b.coarse[3]) + tables.margin;
    const Mask coarseClear =
        greater(squaredCentreDistance(coarse[ia], coarse[ib]), broadcast<V>(coarseReach * coarseReach));
    if (allOf(coarseClear | unsure)) continue;
    const V(*fineA)[3] = placement.fineOf(a, ia);
    Mask fineClear = allLanes<V>();
    for (int i = 0; i < a.fineCount; ++i) {
      const float radiusA = tables.fineR[a.fineBegin + i];
      const float reachB = (radiusA + b.coarse[3]) + tables.margin;
      const Mask clearOfB = greater(squaredCentreDistance(fineA[i], coarse[ib]), broadcast<V>(reachB * reachB));
      if (allOf(clearOfB | unsure | coarseClear)) continue;
      const V(*fineB)[3] = placement.fineOf(b, ib);
      Mask sphereClear = allLanes<V>();
      for (int j = 0; j < b.fineCount; ++j) {
        const float reach = (radiusA + tables.fineR[b.fineBegin + j]) + tables.margin;
        sphereClear = sphereClear & greater(squaredCentreDistance(fineA[i], fineB[j]), broadcast<V>(reach * reach));
      }
      fineClear = fineClear & (clearOfB | sphereClear);
    }
    unsure = unsure | ~(coarseClear | fineClear);
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
    V best = broadcast<V>(kFar);
    for (int k = 0; k < body.obstacleCount; ++k) {
      const ObstacleRow& o = tables.obstacles[tables.obstacleIndex[body.obstacleBegin + k]];
      const V coarseGap = obstacleDistance(o, coarse[b]) - broadcast<V>(body.coarse[3]);
      if (allOf(greaterEqual(coarseGap, broadcast<V>(enough[b])))) {
        best = minimum(best, coarseGap);
        continue;
      }
      const V(*fine)[3] = placement.fineOf(body, b);
      V fineGap = broadcast<V>(kFar);
      for (int f = 0; f < body.fineCount; ++f)
        fineGap = minimum(fineGap, obstacleDistance(o, fine[f]) - broadcast<V>(tables.fineR[body.fineBegin + f]));
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
      const V(*fineA)[3] = placement.fineOf(a, ia);
      const V(*fineB)[3] = placement.fineOf(b, ib);
      V fineGap = broadcast<V>(kFar);
      for (int i = 0; i < a.fineCount; ++i) {
        const float radiusA = tables.fineR[a.fineBegin + i];
        for (int j = 0; j < b.fineCount; ++j) {
          fineGap = minimum(fineGap,
                            centreDistance(fineA[i], fineB[j]) - broadcast<V>(radiusA + tables.fineR[b.fineBegin + j]));
        }
      }
      best = maximum(best, fineGap);
    }
    store(out + pair * kLanes, best - margin);
  }
}

}  // namespace
}  // namespace arcplan::collision::detail::prefilter
