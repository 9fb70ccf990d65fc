#pragma once
// The sphere prefilter's forward kinematics for a batch of states: the poses of the chain's links
// in 8 float lanes (or 1 or 8 portable floats), written once for a lane type V like the rest of
// the kernels and included by sphere_kernel.h only (see there for what V must provide). The
// error of everything computed here is bounded in sphere_prefilter.cpp (the margin).
#include "sphere_tables.h"

namespace arcplan::collision::detail::prefilter {
namespace {

// pi/2 split into two floats (Cody-Waite): the high part has 8 significant bits and the multiples
// used below are -4..4, so k * high is exact, and what the middle part leaves of pi/2 (about 1e-11)
// is far below the polynomials' error.
constexpr double kHalfPi = 1.57079632679489661923;
constexpr float kHalfPiHigh = 1.5703125f;
constexpr float kHalfPiMiddle = static_cast<float>(kHalfPi - 1.5703125);
constexpr float kTwoOverPi = static_cast<float>(2.0 / 3.14159265358979323846);

template <class V>
struct Pose {
  V r[9];  // row-major rotation
  V t[3];
};

// sin and cos of x for |x| <= 2 pi + 1e-6: reduced to r in [-pi/4, pi/4] (x = r + k pi/2); sin by a
// degree-7 minimax polynomial (the coefficients of Cephes' single-precision sinf), cos by its Taylor
// polynomial to degree 8 (truncation below 3e-8). Measured over [-2 pi, 2 pi] against long double:
// at most 1.1e-7 off the true values (the degree-9 Taylor sine before it: the same), 2e-6 assumed by the
// margin; FloatGapsAgreeWithDoubleWithinTheMargin checks the whole chain's error.
template <class V>
void sinCos(V x, V& sine, V& cosine) {
  using Mask = typename V::Mask;
  const V k = roundNearest(x * broadcast<V>(kTwoOverPi));
  const V r = (x - k * broadcast<V>(kHalfPiHigh)) - k * broadcast<V>(kHalfPiMiddle);
  const V r2 = r * r;
  const V s = r + (r * r2) * (broadcast<V>(-1.6666654611e-1f) +
                              r2 * (broadcast<V>(8.3321608736e-3f) + r2 * broadcast<V>(-1.9515295891e-4f)));
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

// The rotation of a link whose table row is `permuted` (sphere_tables.h): B = parent · origin takes
// the parent's columns, permuted and signed (no rounding), and the turn by angle θ about e_k mixes
// two of them: column i = cos θ·B_i + sin θ·B_j, column j = cos θ·B_j − sin θ·B_i, with
// (i, j) = (k + 1, k + 2) mod 3. 12 products and 6 sums where a full 3×3 product takes 27 and 18.
template <class V>
void permutedRotation(const LinkRow& row, const V* parent, const V* s, const V* c, V* out) {
  V b[9];
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      const V x = parent[3 * i + row.column[j]];
      b[3 * i + j] = row.sign[j] < 0.0f ? -x : x;
    }
  }
  if (row.axis < 0) {
    for (int e = 0; e < 9; ++e) out[e] = b[e];
    return;
  }
  const int k = row.axis, i = (k + 1) % 3, j = (k + 2) % 3;
  const V sine = row.axisSign < 0.0f ? -*s : *s;
  for (int r = 0; r < 3; ++r) {
    out[3 * r + i] = *c * b[3 * r + i] + sine * b[3 * r + j];
    out[3 * r + j] = *c * b[3 * r + j] - sine * b[3 * r + i];
    out[3 * r + k] = b[3 * r + k];
  }
}

// The rotation of any other link: parent · (c0 + cos q·c1 + sin q·c2), leaving out the terms of
// structurally zero entries (row.zero; near-zero origin entries are snapped to 0 in
// sphere_prefilter.cpp, within the margin) and the arithmetic of constant entries (row.constant).
template <class V>
void generalRotation(const LinkRow& row, const V* parent, const V* s, const V* c, V* out) {
  V local[9];
  for (int i = 0; i < 9; ++i) {
    local[i] = ((row.constant >> i) & 1u)
                   ? broadcast<V>(row.c0[i])
                   : (broadcast<V>(row.c0[i]) + *c * broadcast<V>(row.c1[i])) + *s * broadcast<V>(row.c2[i]);
  }
  if (parent == nullptr) {
    for (int i = 0; i < 9; ++i) out[i] = local[i];
    return;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      V sum = broadcast<V>(0.0f);
      for (int k = 0; k < 3; ++k) {
        if (!((row.zero >> (3 * k + j)) & 1u)) sum = sum + parent[3 * i + k] * local[3 * k + j];
      }
      out[3 * i + j] = sum;
    }
  }
}

// The chain's poses, parents first. Zero offsets cost no operation either (exact zeros left out of
// a sum change none of its bits). The sines and cosines come first, all joints together: independent
// of each other, they overlap in the pipeline, where computed link by link each waited on the chain's
// products (free-space batches 383 -> 358 ns).
template <class V>
void forwardKinematics(const Tables& tables, const float* q, Pose<V>* poses) {
  V sines[kMaxJoints], cosines[kMaxJoints];
  for (int j = 0; j < tables.dof; ++j) sinCos(load<V>(q + j * kLanes), sines[j], cosines[j]);
  for (int l = 0; l < tables.linkCount; ++l) {
    const LinkRow& row = tables.links[l];
    V s = broadcast<V>(0.0f), c = broadcast<V>(1.0f);
    if (row.joint >= 0) {
      s = sines[row.joint];
      c = cosines[row.joint];
    }
    Pose<V>& pose = poses[l];
    if (row.fixedPose) {
      for (int i = 0; i < 9; ++i) pose.r[i] = broadcast<V>(row.fixedR[i]);
      for (int i = 0; i < 3; ++i) pose.t[i] = broadcast<V>(row.fixedT[i]);
      continue;
    }
    if (row.parent < 0) {
      generalRotation<V>(row, nullptr, &s, &c, pose.r);
      for (int i = 0; i < 3; ++i) pose.t[i] = broadcast<V>(row.t[i]);
      continue;
    }
    const Pose<V>& parent = poses[row.parent];
    if (row.permuted) {
      permutedRotation(row, parent.r, &s, &c, pose.r);
    } else {
      generalRotation(row, parent.r, &s, &c, pose.r);
    }
    for (int i = 0; i < 3; ++i) {
      V t = parent.t[i];
      for (int k = 0; k < 3; ++k) {
        if (row.t[k] != 0.0f) t = t + parent.r[3 * i + k] * broadcast<V>(row.t[k]);
      }
      pose.t[i] = t;
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

}  // namespace
}  // namespace arcplan::collision::detail::prefilter
