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

}  // namespace arcplan::collision::detail::prefilter
