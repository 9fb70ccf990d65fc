// The sphere prefilter's kernels on 8 AVX2 float lanes. Built with -mavx2 (and no -mfma: the
// portable path has no fused multiply-add either) only on x86-64 (collision/CMakeLists.txt);
// SpherePrefilter calls it only when the CPU reports AVX2, so the library runs on any x86-64.
#include <immintrin.h>

#include "sphere_tables.h"

namespace arcplan::collision::detail::prefilter {
namespace {

struct Avx2Mask {
  __m256 m;
};

struct Avx2Lanes {
  static constexpr int kLanes = 8;
  using Mask = Avx2Mask;
  __m256 v;
};

using V = Avx2Lanes;
using Mask = Avx2Mask;

template <class>
V broadcast(float x) {
  return {_mm256_set1_ps(x)};
}
template <class>
V load(const float* p) {
  return {_mm256_loadu_ps(p)};
}
inline void store(float* p, V a) { _mm256_storeu_ps(p, a.v); }
inline V operator+(V a, V b) { return {_mm256_add_ps(a.v, b.v)}; }
inline V operator-(V a, V b) { return {_mm256_sub_ps(a.v, b.v)}; }
inline V operator*(V a, V b) { return {_mm256_mul_ps(a.v, b.v)}; }
inline V operator-(V a) { return {_mm256_xor_ps(a.v, _mm256_set1_ps(-0.0f))}; }
inline V squareRoot(V a) { return {_mm256_sqrt_ps(a.v)}; }
inline V minimum(V a, V b) { return {_mm256_min_ps(a.v, b.v)}; }  // a < b ? a : b
inline V maximum(V a, V b) { return {_mm256_max_ps(a.v, b.v)}; }  // a > b ? a : b
inline V absolute(V a) { return {_mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.v)}; }
inline V roundNearest(V a) { return {_mm256_round_ps(a.v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)}; }
inline V floorOf(V a) { return {_mm256_floor_ps(a.v)}; }
inline Mask greater(V a, V b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)}; }
inline Mask greaterEqual(V a, V b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GE_OQ)}; }
inline Mask equal(V a, V b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_EQ_OQ)}; }
inline Mask operator|(Mask a, Mask b) { return {_mm256_or_ps(a.m, b.m)}; }
inline Mask operator&(Mask a, Mask b) { return {_mm256_and_ps(a.m, b.m)}; }
inline Mask operator~(Mask a) { return {_mm256_xor_ps(a.m, _mm256_castsi256_ps(_mm256_set1_epi32(-1)))}; }
template <class>
Mask allLanes() {
  return {_mm256_castsi256_ps(_mm256_set1_epi32(-1))};
}
inline V select(Mask m, V a, V b) { return {_mm256_blendv_ps(b.v, a.v, m.m)}; }
inline bool allOf(Mask m) { return _mm256_movemask_ps(m.m) == 0xFF; }
inline std::uint32_t bits(Mask m) { return static_cast<std::uint32_t>(_mm256_movemask_ps(m.m)); }

}  // namespace
}  // namespace arcplan::collision::detail::prefilter

#include "sphere_kernel.h"

namespace arcplan::collision::detail::prefilter {

std::uint32_t freeLanesAvx2(const Tables& tables, const float* q, int lanes) {
  return freeLanes<Avx2Lanes>(tables, q) & ((1u << lanes) - 1u);
}

void gapsAvx2(const Tables& tables, const float* q, const float* enough, float* out) {
  gaps<Avx2Lanes>(tables, q, enough, out);
}

// Four joints of the 8 states at a time: each state's 4 doubles converted to 4 floats, then an 8 × 4
// transpose (states k and k + 4 share a register, a 4 × 4 transpose in each half). Converting and
// storing the 48 values of a UR batch one by one took 32 ns, a tenth of a free-space batch.
bool loadLanesAvx2(const double* states, std::int64_t stride, int dof, int lanes, float* q) {
  const double* state[kLanes];
  for (int lane = 0; lane < kLanes; ++lane) state[lane] = states + (lane < lanes ? lane : 0) * stride;
  const __m256d magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
  const __m256d largest = _mm256_set1_pd(kLargestAngle);
  __m256d beyond = _mm256_setzero_pd();
  int j = 0;
  for (; j + 4 <= dof; j += 4) {
    __m128 f[kLanes];
    for (int lane = 0; lane < kLanes; ++lane) {
      const __m256d d = _mm256_loadu_pd(state[lane] + j);
      // Not |d| <= largest: beyond it, or NaN.
      beyond = _mm256_or_pd(beyond, _mm256_cmp_pd(_mm256_and_pd(d, magnitude), largest, _CMP_NLE_UQ));
      f[lane] = _mm256_cvtpd_ps(d);
    }
    const __m256 r0 = _mm256_set_m128(f[4], f[0]), r1 = _mm256_set_m128(f[5], f[1]);
    const __m256 r2 = _mm256_set_m128(f[6], f[2]), r3 = _mm256_set_m128(f[7], f[3]);
    const __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1);
    const __m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3);
    _mm256_storeu_ps(q + j * kLanes, _mm256_shuffle_ps(t0, t2, 0x44));
    _mm256_storeu_ps(q + (j + 1) * kLanes, _mm256_shuffle_ps(t0, t2, 0xEE));
    _mm256_storeu_ps(q + (j + 2) * kLanes, _mm256_shuffle_ps(t1, t3, 0x44));
    _mm256_storeu_ps(q + (j + 3) * kLanes, _mm256_shuffle_ps(t1, t3, 0xEE));
  }
  bool inRange = _mm256_movemask_pd(beyond) == 0;
  for (; j < dof; ++j) {
    for (int lane = 0; lane < kLanes; ++lane) {
      const double x = state[lane][j];
      inRange = inRange & (x <= kLargestAngle && x >= -kLargestAngle);
      q[j * kLanes + lane] = static_cast<float>(x);
    }
  }
  return inRange;
}

}  // namespace arcplan::collision::detail::prefilter
