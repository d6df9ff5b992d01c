#include "cuts/node_lanes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define MANYLIGHT_AVX2_LANES 1
#include <immintrin.h>
#endif

namespace manylight {

namespace one_lane {

using V = float;
MANYLIGHT_INLINE inline V splat(float x) { return x; }
MANYLIGHT_INLINE inline V load(const float* p) { return *p; }
MANYLIGHT_INLINE inline void store(float* p, V v) { *p = v; }
MANYLIGHT_INLINE inline V vsqrt(V x) { return std::sqrt(x); }
MANYLIGHT_INLINE inline V vabs(V x) { return std::abs(x); }
MANYLIGHT_INLINE inline V vmin(V a, V b) { return std::min(a, b); }
MANYLIGHT_INLINE inline V vmax(V a, V b) { return std::max(a, b); }
MANYLIGHT_INLINE inline std::uint32_t bitsOf(V x) {
  std::uint32_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
MANYLIGHT_INLINE inline V floatOfBits(std::uint32_t b) {
  V x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}
MANYLIGHT_INLINE inline V vexponent(V x) { return float(int((bitsOf(x) >> 23) & 0xffu) - 127); }
MANYLIGHT_INLINE inline V vmantissa(V x) {
  return floatOfBits((bitsOf(x) & 0x7fffffu) | 0x3f800000u);
}
MANYLIGHT_INLINE inline V vexp2Integer(V k) {
  return floatOfBits(std::uint32_t(int(k) + 127) << 23);
}
#include "cuts/node_lanes_kernel.h"

}  // namespace one_lane

#ifdef MANYLIGHT_AVX2_LANES
#pragma GCC push_options
#pragma GCC target("avx2")
namespace eight_lanes {

using V = __m256;
MANYLIGHT_INLINE inline V splat(float x) { return _mm256_set1_ps(x); }
MANYLIGHT_INLINE inline V load(const float* p) { return _mm256_loadu_ps(p); }
MANYLIGHT_INLINE inline void store(float* p, V v) { _mm256_storeu_ps(p, v); }
MANYLIGHT_INLINE inline V vsqrt(V x) { return _mm256_sqrt_ps(x); }
MANYLIGHT_INLINE inline V vabs(V x) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), x); }
// MINPS and MAXPS return their second operand when the comparison is false (NaN, equal), as
// std::min(a, b) = (b < a) ? b : a and std::max(a, b) = (a < b) ? b : a return a.
MANYLIGHT_INLINE inline V vmin(V a, V b) { return _mm256_min_ps(b, a); }
MANYLIGHT_INLINE inline V vmax(V a, V b) { return _mm256_max_ps(b, a); }
MANYLIGHT_INLINE inline V vexponent(V x) {
  const __m256i b = _mm256_srli_epi32(_mm256_castps_si256(x), 23);
  return _mm256_cvtepi32_ps(
      _mm256_sub_epi32(_mm256_and_si256(b, _mm256_set1_epi32(0xff)), _mm256_set1_epi32(127)));
}
MANYLIGHT_INLINE inline V vmantissa(V x) {
  const __m256i b = _mm256_and_si256(_mm256_castps_si256(x), _mm256_set1_epi32(0x7fffff));
  return _mm256_castsi256_ps(_mm256_or_si256(b, _mm256_set1_epi32(0x3f800000)));
}
// k is integral, so rounding it to an integer (CVTPS2DQ) is exact, as the one lane's int(k).
MANYLIGHT_INLINE inline V vexp2Integer(V k) {
  const __m256i e = _mm256_add_epi32(_mm256_cvtps_epi32(k), _mm256_set1_epi32(127));
  return _mm256_castsi256_ps(_mm256_slli_epi32(e, 23));
}
#include "cuts/node_lanes_kernel.h"

void nodeBounds(const RegionTerms& region, const NodeLanes& in, BoundLanes& out) {
  nodeBoundLanes(region, in, 0, out);
}

void foldBounds(const RegionTerms& region, const FoldLanes& in, float* t) {
  foldBoundLanes(region, in, 0, t);
}

void lobePowers(const float* x, float e, float* upper, float* lower, float* estimate) {
  const V v = load(x);
  store(upper, powUpperLanes(v, e));
  store(lower, powLowerLanes(v, e));
  store(estimate, powLanes(v, e));
}

void addFarField(glm::vec3 centre, const FarLanes& in, int count, FarSums& sums) {
  farFieldLanes(centre, in, count, 0, sums);
}

// Eight rows of eight floats (one per node) into eight rows of eight lanes.
void gatherNodes(const float* const given[kLanes], int count, NodeLanes& out) {
  const float* nodes[kLanes];
  for (int l = 0; l < kLanes; ++l) nodes[l] = given[l < count ? l : 0];
  float* rows = reinterpret_cast<float*>(&out);
  for (int block = 0; block < kNodeRows; block += 8) {
    __m256 r[8];
    for (int k = 0; k < 8; ++k) r[k] = _mm256_load_ps(nodes[k] + block);
    __m256 t[8], u[8];
    for (int k = 0; k < 8; k += 2) {
      t[k] = _mm256_unpacklo_ps(r[k], r[k + 1]);
      t[k + 1] = _mm256_unpackhi_ps(r[k], r[k + 1]);
    }
    for (int k = 0; k < 8; k += 4) {
      u[k] = _mm256_shuffle_ps(t[k], t[k + 2], _MM_SHUFFLE(1, 0, 1, 0));
      u[k + 1] = _mm256_shuffle_ps(t[k], t[k + 2], _MM_SHUFFLE(3, 2, 3, 2));
      u[k + 2] = _mm256_shuffle_ps(t[k + 1], t[k + 3], _MM_SHUFFLE(1, 0, 1, 0));
      u[k + 3] = _mm256_shuffle_ps(t[k + 1], t[k + 3], _MM_SHUFFLE(3, 2, 3, 2));
    }
    for (int k = 0; k < 4; ++k) {
      _mm256_storeu_ps(rows + (block + k) * kLanes, _mm256_permute2f128_ps(u[k], u[k + 4], 0x20));
      _mm256_storeu_ps(rows + (block + k + 4) * kLanes,
                       _mm256_permute2f128_ps(u[k], u[k + 4], 0x31));
    }
  }
}

}  // namespace eight_lanes
#pragma GCC pop_options
#endif

bool wideNodeBounds() {
#ifdef MANYLIGHT_AVX2_LANES
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
#else
  return false;
#endif
}

// In the functions below: where `wide` is asked for and the CPU has AVX2, calls
// eight_lanes::`call` and returns; else they go on one lane at a time.
#ifdef MANYLIGHT_AVX2_LANES
#define MANYLIGHT_EIGHT_LANES(call) \
  if (wide && wideNodeBounds()) {   \
    eight_lanes::call;              \
    return;                         \
  }
#else
#define MANYLIGHT_EIGHT_LANES(call) (void)wide
#endif

void nodeBounds(const RegionTerms& region, const NodeLanes& in, int count, BoundLanes& out,
                bool wide) {
  MANYLIGHT_EIGHT_LANES(nodeBounds(region, in, out));
  for (int l = 0; l < count; ++l) one_lane::nodeBoundLanes(region, in, l, out);
}

void foldBounds(const RegionTerms& region, const FoldLanes& in, int count, float t[kLanes],
                bool wide) {
  MANYLIGHT_EIGHT_LANES(foldBounds(region, in, t));
  for (int l = 0; l < count; ++l) one_lane::foldBoundLanes(region, in, l, t);
}

void lobePowers(const float x[kLanes], float e, float upper[kLanes], float lower[kLanes],
                float estimate[kLanes], bool wide) {
  MANYLIGHT_EIGHT_LANES(lobePowers(x, e, upper, lower, estimate));
  for (int l = 0; l < kLanes; ++l) {
    upper[l] = one_lane::powUpperLanes(x[l], e);
    lower[l] = one_lane::powLowerLanes(x[l], e);
    estimate[l] = one_lane::powLanes(x[l], e);
  }
}

void gatherNodes(const float* const nodes[kLanes], int count, NodeLanes& out, bool wide) {
  MANYLIGHT_EIGHT_LANES(gatherNodes(nodes, count, out));
  float* rows = reinterpret_cast<float*>(&out);
  for (int l = 0; l < kLanes; ++l) {
    float node[kNodeRows];
    std::memcpy(node, nodes[l < count ? l : 0], sizeof node);
    for (int row = 0; row < kNodeRows; ++row) rows[row * kLanes + l] = node[row];
  }
}

void addFarField(glm::vec3 centre, const FarLanes& in, int count, FarSums& sums, bool wide) {
  MANYLIGHT_EIGHT_LANES(addFarField(centre, in, count, sums));
  for (int l = 0; l < count; ++l) one_lane::farFieldLanes(centre, in, count, l, sums);
}

}  // namespace manylight
