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
#include "sphere_tables.h"

namespace arcplan::collision::detail::prefilter {
namespace {

// pi/2 split into three floats (Cody-Waite): the high part has 8 significant bits and the
// multiples used below are -2..2, so k * part is exact and x - k * pi/2 loses nothing to rounding.
constexpr double kHalfPi = 1.57079632679489661923;
constexpr float kHalfPiHigh = 1.5703125f;
constexpr float kHalfPiMiddle = static_cast<float>(kHalfPi - 1.5703125);
constexpr float kHalfPiLow = static_cast<float>(kHalfPi - 1.5703125 - static_cast<double>(kHalfPiMiddle));
constexpr float kTwoOverPi = static_cast<float>(2.0 / 3.14159265358979323846);
constexpr float kFar = 1e30f;  // "no pair measured": larger than any distance

template <class V>
struct Pose {
  V r[9];  // row-major rotation
  V t[3];
};

// sin and cos of x for |x| <= pi + 1e-6: reduced to r in [-pi/4, pi/4] (x = r + k pi/2), Taylor
// polynomials to degree 9 (sin) and 8 (cos) whose truncation errors there are below 2e-9 and 3e-8;
// with rounding the results stay within 5e-7 of the true values (measured by the tests, 2e-6 assumed
// by the margin).
template <class V>
void sinCos(V x, V& sine, V& cosine) {
  using Mask = typename V::Mask;
  const V k = roundNearest(x * broadcast<V>(kTwoOverPi));
  const V r = ((x - k * broadcast<V>(kHalfPiHigh)) - k * broadcast<V>(kHalfPiMiddle)) - k * broadcast<V>(kHalfPiLow);
  const V r2 = r * r;
  const V s = r + (r * r2) * (broadcast<V>(-1.0f / 6.0f) +
                              r2 * (broadcast<V>(1.0f / 120.0f) +
                                    r2 * (broadcast<V>(-1.0f / 5040.0f) + r2 * broadcast<V>(1.0f / 362880.0f))));
  const V c =
      broadcast<V>(1.0f) +
      r2 * (broadcast<V>(-0.5f) + r2 * (broadcast<V>(1.0f / 24.0f) +
                                        r2 * (broadcast<V>(-1.0f / 720.0f) + r2 * broadcast<V>(1.0f / 40320.0f))));
  const V quadrant = k - broadcast<V>(4.0f) * floorOf(k * broadcast<V>(0.25f));  // k mod 4, in 0..3
  const Mask q1 = equal(quadrant, broadcast<V>(1.0f)), q2 = equal(quadrant, broadcast<V>(2.0f)),
             q3 = equal(quadrant, broadcast<V>(3.0f));
  sine = select(q1, c, select(q2, -s, select(q3, -c, s)));
  cosine = select(q1, -s, select(q2, -c, select(q3, s, c)));
}

template <class V>
void forwardKinematics(const Tables& tables, const float* q, Pose<V>* poses) {
  for (int l = 0; l < tables.linkCount; ++l) {
    const LinkRow& row = tables.links[l];
    V local[9];
    if (row.joint >= 0) {
      V s, c;
      sinCos(load<V>(q + row.joint * kLanes), s, c);
      for (int i = 0; i < 9; ++i)
        local[i] = (broadcast<V>(row.c0[i]) + c * broadcast<V>(row.c1[i])) + s * broadcast<V>(row.c2[i]);
    } else {
      for (int i = 0; i < 9; ++i) local[i] = broadcast<V>(row.c0[i]);
    }
    Pose<V>& pose = poses[l];
    if (row.parent < 0) {
      for (int i = 0; i < 9; ++i) pose.r[i] = local[i];
      for (int i = 0; i < 3; ++i) pose.t[i] = broadcast<V>(row.t[i]);
      continue;
    }
    const Pose<V>& parent = poses[row.parent];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        pose.r[3 * i + j] =
            (parent.r[3 * i] * local[j] + parent.r[3 * i + 1] * local[3 + j]) + parent.r[3 * i + 2] * local[6 + j];
      }
      pose.t[i] = ((parent.r[3 * i] * broadcast<V>(row.t[0]) + parent.r[3 * i + 1] * broadcast<V>(row.t[1])) +
                   parent.r[3 * i + 2] * broadcast<V>(row.t[2])) +
                  parent.t[i];
    }
  }
}

template <class V>
void place(const Pose<V>& pose, float x, float y, float z, V* out) {
  for (int i = 0; i < 3; ++i) {
    out[i] = ((pose.r[3 * i] * broadcast<V>(x) + pose.r[3 * i + 1] * broadcast<V>(y)) +
              pose.r[3 * i + 2] * broadcast<V>(z)) +
             pose.t[i];
  }
}

template <class V>
void placeFine(const Tables& tables, const BodyRow& body, const Pose<V>* poses, V (*out)[3]) {
  for (int f = 0; f < body.fineCount; ++f) {
    const int k = body.fineBegin + f;
    place(poses[body.link], tables.fineX[k], tables.fineY[k], tables.fineZ[k], out[f]);
  }
}

// Distance of the world point p from the obstacle's volume (<= 0 inside a sphere, 0 inside a box or cylinder).
template <class V>
V obstacleDistance(const ObstacleRow& o, const V* p) {
  V l[3];
  for (int i = 0; i < 3; ++i) {
    l[i] = ((broadcast<V>(o.rotation[3 * i]) * p[0] + broadcast<V>(o.rotation[3 * i + 1]) * p[1]) +
            broadcast<V>(o.rotation[3 * i + 2]) * p[2]) +
           broadcast<V>(o.translation[i]);
  }
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

template <class V>
V centreDistance(const V* a, const V* b) {
  const V dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return squareRoot((dx * dx + dy * dy) + dz * dz);
}

// A lane is decided by its own numbers only: clear by its coarse sphere, or by every fine sphere.
// Which lanes reach the fine spheres depends on the batch, but not a lane's decision, so one state
// gets the same answer alone or in any batch.
template <class V>
std::uint32_t freeLanes(const Tables& tables, const float* q) {
  using Mask = typename V::Mask;
  Pose<V> poses[kMaxLinks];
  forwardKinematics(tables, q, poses);
  const V margin = broadcast<V>(tables.margin);
  Mask unsure = ~allLanes<V>();
  V fineA[kMaxFinePerBody][3], fineB[kMaxFinePerBody][3];
  for (int b = 0; b < tables.bodyCount; ++b) {
    const BodyRow& body = tables.bodies[b];
    V centre[3];
    place(poses[body.link], body.coarse[0], body.coarse[1], body.coarse[2], centre);
    const V coarseRadius = broadcast<V>(body.coarse[3]);
    bool placed = false;
    for (int k = 0; k < body.obstacleCount; ++k) {
      const ObstacleRow& o = tables.obstacles[tables.obstacleIndex[body.obstacleBegin + k]];
      const Mask coarseClear = greater(obstacleDistance(o, centre) - coarseRadius, margin);
      if (allOf(coarseClear | unsure)) continue;
      if (!placed) placeFine(tables, body, poses, fineA);
      placed = true;
      Mask fineClear = allLanes<V>();
      for (int f = 0; f < body.fineCount && !allOf(unsure | coarseClear | ~fineClear); ++f) {
        const V gap = obstacleDistance(o, fineA[f]) - broadcast<V>(tables.fineR[body.fineBegin + f]);
        fineClear = fineClear & greater(gap, margin);
      }
      unsure = unsure | ~(coarseClear | fineClear);
      if (allOf(unsure)) return 0;
    }
  }
  for (int p = 0; p < tables.selfPairCount; ++p) {
    const BodyRow& a = tables.bodies[tables.selfPairs[2 * p]];
    const BodyRow& b = tables.bodies[tables.selfPairs[2 * p + 1]];
    V centreA[3], centreB[3];
    place(poses[a.link], a.coarse[0], a.coarse[1], a.coarse[2], centreA);
    place(poses[b.link], b.coarse[0], b.coarse[1], b.coarse[2], centreB);
    const V coarseGap = centreDistance(centreA, centreB) - broadcast<V>(a.coarse[3] + b.coarse[3]);
    const Mask coarseClear = greater(coarseGap, margin);
    if (allOf(coarseClear | unsure)) continue;
    placeFine(tables, a, poses, fineA);
    placeFine(tables, b, poses, fineB);
    Mask fineClear = allLanes<V>();
    for (int i = 0; i < a.fineCount && !allOf(unsure | coarseClear | ~fineClear); ++i) {
      const float radiusA = tables.fineR[a.fineBegin + i];
      for (int j = 0; j < b.fineCount; ++j) {
        const V gap = centreDistance(fineA[i], fineB[j]) - broadcast<V>(radiusA + tables.fineR[b.fineBegin + j]);
        fineClear = fineClear & greater(gap, margin);
      }
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
  const V margin = broadcast<V>(tables.margin);
  V fineA[kMaxFinePerBody][3], fineB[kMaxFinePerBody][3];
  for (int b = 0; b < tables.bodyCount; ++b) {
    const BodyRow& body = tables.bodies[b];
    V centre[3];
    place(poses[body.link], body.coarse[0], body.coarse[1], body.coarse[2], centre);
    const V coarseRadius = broadcast<V>(body.coarse[3]);
    V best = broadcast<V>(kFar);
    bool placed = false;
    for (int k = 0; k < body.obstacleCount; ++k) {
      const ObstacleRow& o = tables.obstacles[tables.obstacleIndex[body.obstacleBegin + k]];
      const V coarse = obstacleDistance(o, centre) - coarseRadius;
      if (allOf(greaterEqual(coarse, broadcast<V>(enough[b])))) {
        best = minimum(best, coarse);
        continue;
      }
      if (!placed) placeFine(tables, body, poses, fineA);
      placed = true;
      V fine = broadcast<V>(kFar);
      for (int f = 0; f < body.fineCount; ++f)
        fine = minimum(fine, obstacleDistance(o, fineA[f]) - broadcast<V>(tables.fineR[body.fineBegin + f]));
      best = minimum(best, maximum(coarse, fine));
    }
    store(out + b * kLanes, best - margin);
  }
  for (int p = 0; p < tables.selfPairCount; ++p) {
    const BodyRow& a = tables.bodies[tables.selfPairs[2 * p]];
    const BodyRow& b = tables.bodies[tables.selfPairs[2 * p + 1]];
    V centreA[3], centreB[3];
    place(poses[a.link], a.coarse[0], a.coarse[1], a.coarse[2], centreA);
    place(poses[b.link], b.coarse[0], b.coarse[1], b.coarse[2], centreB);
    V best = centreDistance(centreA, centreB) - broadcast<V>(a.coarse[3] + b.coarse[3]);
    const int pair = tables.bodyCount + p;
    if (!allOf(greaterEqual(best, broadcast<V>(enough[pair])))) {
      placeFine(tables, a, poses, fineA);
      placeFine(tables, b, poses, fineB);
      V fine = broadcast<V>(kFar);
      for (int i = 0; i < a.fineCount; ++i) {
        const float radiusA = tables.fineR[a.fineBegin + i];
        for (int j = 0; j < b.fineCount; ++j)
          fine =
              minimum(fine, centreDistance(fineA[i], fineB[j]) - broadcast<V>(radiusA + tables.fineR[b.fineBegin + j]));
      }
      best = maximum(best, fine);
    }
    store(out + pair * kLanes, best - margin);
  }
}

}  // namespace
}  // namespace arcplan::collision::detail::prefilter
