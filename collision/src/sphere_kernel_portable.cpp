// The sphere prefilter's kernels on plain floats, for any CPU: the same operations in the same
// order as the AVX2 path (sphere_kernel.h), lane by lane, so both give the same decisions. One
// lane for single states, eight for batches.
#include <cmath>

#include "sphere_tables.h"

namespace arcplan::collision::detail::prefilter {
namespace {

template <int N>
struct PortableMask {
  bool m[N];
};

template <int N>
struct PortableLanes {
  static constexpr int kLanes = N;
  using Mask = PortableMask<N>;
  float v[N];
};

template <int N, class F>
PortableLanes<N> each(F f) {
  PortableLanes<N> r;
  for (int i = 0; i < N; ++i) r.v[i] = f(i);
  return r;
}

template <int N, class F>
PortableMask<N> eachMask(F f) {
  PortableMask<N> r;
  for (int i = 0; i < N; ++i) r.m[i] = f(i);
  return r;
}

template <class V>
V broadcast(float x) {
  return each<V::kLanes>([x](int) { return x; });
}
template <class V>
V load(const float* p) {
  return each<V::kLanes>([p](int i) { return p[i]; });
}

template <int N>
PortableLanes<N> operator+(PortableLanes<N> a, PortableLanes<N> b) {
  return each<N>([&](int i) { return a.v[i] + b.v[i]; });
}
template <int N>
PortableLanes<N> operator-(PortableLanes<N> a, PortableLanes<N> b) {
  return each<N>([&](int i) { return a.v[i] - b.v[i]; });
}
template <int N>
PortableLanes<N> operator*(PortableLanes<N> a, PortableLanes<N> b) {
  return each<N>([&](int i) { return a.v[i] * b.v[i]; });
}
template <int N>
PortableLanes<N> operator-(PortableLanes<N> a) {
  return each<N>([&](int i) { return -a.v[i]; });
}
template <int N>
PortableLanes<N> squareRoot(PortableLanes<N> a) {
  return each<N>([&](int i) { return std::sqrt(a.v[i]); });
}
// As MINPS and MAXPS: the second operand when the comparison fails (also for NaN).
template <int N>
PortableLanes<N> minimum(PortableLanes<N> a, PortableLanes<N> b) {
  return each<N>([&](int i) { return a.v[i] < b.v[i] ? a.v[i] : b.v[i]; });
}
template <int N>
PortableLanes<N> maximum(PortableLanes<N> a, PortableLanes<N> b) {
  return each<N>([&](int i) { return a.v[i] > b.v[i] ? a.v[i] : b.v[i]; });
}
template <int N>
PortableLanes<N> absolute(PortableLanes<N> a) {
  return each<N>([&](int i) { return std::fabs(a.v[i]); });
}
template <int N>
PortableLanes<N> roundNearest(PortableLanes<N> a) {
  return each<N>([&](int i) { return std::nearbyint(a.v[i]); });  // default rounding: ties to even
}
template <int N>
PortableLanes<N> floorOf(PortableLanes<N> a) {
  return each<N>([&](int i) { return std::floor(a.v[i]); });
}
template <int N>
PortableMask<N> greater(PortableLanes<N> a, PortableLanes<N> b) {
  return eachMask<N>([&](int i) { return a.v[i] > b.v[i]; });
}
template <int N>
PortableMask<N> greaterEqual(PortableLanes<N> a, PortableLanes<N> b) {
  return eachMask<N>([&](int i) { return a.v[i] >= b.v[i]; });
}
template <int N>
PortableMask<N> equal(PortableLanes<N> a, PortableLanes<N> b) {
  return eachMask<N>([&](int i) { return a.v[i] == b.v[i]; });
}
template <int N>
PortableMask<N> operator|(PortableMask<N> a, PortableMask<N> b) {
  return eachMask<N>([&](int i) { return a.m[i] || b.m[i]; });
}
template <int N>
PortableMask<N> operator&(PortableMask<N> a, PortableMask<N> b) {
  return eachMask<N>([&](int i) { return a.m[i] && b.m[i]; });
}
template <int N>
PortableMask<N> operator~(PortableMask<N> a) {
  return eachMask<N>([&](int i) { return !a.m[i]; });
}
template <class V>
typename V::Mask allLanes() {
  return eachMask<V::kLanes>([](int) { return true; });
}
template <int N>
PortableLanes<N> select(PortableMask<N> m, PortableLanes<N> a, PortableLanes<N> b) {
  return each<N>([&](int i) { return m.m[i] ? a.v[i] : b.v[i]; });
}
template <int N>
bool allOf(PortableMask<N> m) {
  for (int i = 0; i < N; ++i)
    if (!m.m[i]) return false;
  return true;
}
template <int N>
std::uint32_t bits(PortableMask<N> m) {
  std::uint32_t result = 0;
  for (int i = 0; i < N; ++i) result |= static_cast<std::uint32_t>(m.m[i]) << i;
  return result;
}
template <int N>
void store(float* p, PortableLanes<N> a) {
  for (int i = 0; i < N; ++i) p[i] = a.v[i];
}

}  // namespace
}  // namespace arcplan::collision::detail::prefilter

#include "sphere_kernel.h"

namespace arcplan::collision::detail::prefilter {

std::uint32_t freeLanesPortable(const Tables& tables, const float* q, int lanes) {
  if (lanes == 1) return freeLanes<PortableLanes<1>>(tables, q);
  return freeLanes<PortableLanes<kLanes>>(tables, q) & ((1u << lanes) - 1u);
}

void gapsPortable(const Tables& tables, const float* q, const float* enough, float* out) {
  gaps<PortableLanes<kLanes>>(tables, q, enough, out);
}

bool loadLanesPortable(const double* states, std::int64_t stride, int dof, int lanes, float* q) {
  bool inRange = true;
  for (int lane = 0; lane < kLanes; ++lane) {
    const double* state = states + (lane < lanes ? lane : 0) * stride;
    for (int j = 0; j < dof; ++j) {
      inRange = inRange & (std::fabs(state[j]) <= kLargestAngle);
      q[j * kLanes + lane] = static_cast<float>(state[j]);
    }
  }
  return inRange;
}

}  // namespace arcplan::collision::detail::prefilter
