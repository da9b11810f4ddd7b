#include "band_count.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#if defined(__x86_64__) && defined(__SSE2__)
#include <immintrin.h>
#define BIMLOC_BAND_COUNT_X86 1
#endif

namespace bimloc::planes::detail {
namespace {

// How often the count asks whether the points left can still beat the best: a block is cheap,
// the question nearly free, and most hypotheses are hopeless well before the pool's end.
constexpr std::size_t kBandCheckEvery = 256;

inline bool inBandPacked(float a, float b, float c, float d, float t, float x, float y, float z) {
  return std::abs((a * x + b * y) + (c * z + d)) < t;
}
inline bool inBandTail(float a, float b, float c, float d, float t, float x, float y, float z) {
  return std::abs(a * x + b * y + c * z + d) < t;
}

// The last n % 4 points, as the SSE2 loop's scalar tail counted them.
std::size_t countTail(const float* x, const float* y, const float* z, std::size_t from, std::size_t n, float a, float b, float c,
                      float d, float t) {
  std::size_t count = 0;
  for (std::size_t i = from; i < n; ++i) count += inBandTail(a, b, c, d, t, x[i], y[i], z[i]);
  return count;
}

#if BIMLOC_BAND_COUNT_X86
std::size_t countSse2(const float* x, const float* y, const float* z, std::size_t n, float a, float b, float c, float d, float t,
                      std::size_t best) {
  const std::size_t packed = n & ~std::size_t(3);
  const __m128 va = _mm_set1_ps(a), vb = _mm_set1_ps(b), vc = _mm_set1_ps(c), vd = _mm_set1_ps(d);
  const __m128 vt = _mm_set1_ps(t), sign = _mm_set1_ps(-0.0f);
  std::size_t count = 0;
  for (std::size_t i = 0; i < packed;) {
    const std::size_t end = std::min(packed, i + kBandCheckEvery);
    __m128i lanes = _mm_setzero_si128();  // an inlier's mask lane is -1
    for (; i < end; i += 4) {
      const __m128 r = _mm_add_ps(_mm_add_ps(_mm_mul_ps(va, _mm_loadu_ps(x + i)), _mm_mul_ps(vb, _mm_loadu_ps(y + i))),
                                  _mm_add_ps(_mm_mul_ps(vc, _mm_loadu_ps(z + i)), vd));
      lanes = _mm_sub_epi32(lanes, _mm_castps_si128(_mm_cmplt_ps(_mm_andnot_ps(sign, r), vt)));
    }
    alignas(16) std::int32_t sums[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(sums), lanes);
    count += std::size_t(sums[0]) + std::size_t(sums[1]) + std::size_t(sums[2]) + std::size_t(sums[3]);
    if (count + (n - i) <= best) return count;
  }
  return count + countTail(x, y, z, packed, n, a, b, c, d, t);
}

// Eight points at a time, the same float operations as countSse2's four (AVX2 without FMA:
// no fused multiply-add can change a rounding).
__attribute__((target("avx2"))) std::size_t countAvx2(const float* x, const float* y, const float* z, std::size_t n, float a,
                                                      float b, float c, float d, float t, std::size_t best) {
  const std::size_t packed = n & ~std::size_t(3), wide = n & ~std::size_t(7);
  const __m256 va = _mm256_set1_ps(a), vb = _mm256_set1_ps(b), vc = _mm256_set1_ps(c), vd = _mm256_set1_ps(d);
  const __m256 vt = _mm256_set1_ps(t), sign = _mm256_set1_ps(-0.0f);
  std::size_t count = 0, i = 0;
  while (i < wide) {
    const std::size_t end = std::min(wide, i + kBandCheckEvery);
    __m256i lanes = _mm256_setzero_si256();
    for (; i < end; i += 8) {
      const __m256 r =
          _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(va, _mm256_loadu_ps(x + i)), _mm256_mul_ps(vb, _mm256_loadu_ps(y + i))),
                        _mm256_add_ps(_mm256_mul_ps(vc, _mm256_loadu_ps(z + i)), vd));
      lanes = _mm256_sub_epi32(lanes, _mm256_castps_si256(_mm256_cmp_ps(_mm256_andnot_ps(sign, r), vt, _CMP_LT_OS)));
    }
    alignas(32) std::int32_t sums[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(sums), lanes);
    for (const std::int32_t s : sums) count += std::size_t(s);
    if (count + (n - i) <= best) return count;
  }
  for (; i < packed; ++i) count += inBandPacked(a, b, c, d, t, x[i], y[i], z[i]);
  return count + countTail(x, y, z, packed, n, a, b, c, d, t);
}

bool hasAvx2() {
  static const bool yes = [] {
    __builtin_cpu_init();  // harmless when libgcc's constructor has run it already
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return yes;
}
#endif

// Eigen's Vector3f::dot(p) + d (its unrolled sum: the first product plus the sum of the other two).
inline bool nearPlane(float nx, float ny, float nz, float d, float t, float x, float y, float z) {
  return !(std::abs(nx * x + (ny * y + nz * z) + d) > t);
}

void indicesInBandPlain(const float* x, const float* y, const float* z, std::size_t from, std::size_t n, float nx, float ny,
                        float nz, float d, float t, std::vector<int>& out) {
  for (std::size_t i = from; i < n; ++i)
    if (nearPlane(nx, ny, nz, d, t, x[i], y[i], z[i])) out.push_back(static_cast<int>(i));
}

#if BIMLOC_BAND_COUNT_X86
__attribute__((target("avx2"))) void indicesInBandAvx2(const float* x, const float* y, const float* z, std::size_t n, float nx,
                                                       float ny, float nz, float d, float t, std::vector<int>& out) {
  const std::size_t wide = n & ~std::size_t(7);
  const __m256 vx = _mm256_set1_ps(nx), vy = _mm256_set1_ps(ny), vz = _mm256_set1_ps(nz), vd = _mm256_set1_ps(d);
  const __m256 vt = _mm256_set1_ps(t), sign = _mm256_set1_ps(-0.0f);
  for (std::size_t i = 0; i < wide; i += 8) {
    const __m256 r = _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(vx, _mm256_loadu_ps(x + i)),
                      _mm256_add_ps(_mm256_mul_ps(vy, _mm256_loadu_ps(y + i)), _mm256_mul_ps(vz, _mm256_loadu_ps(z + i)))),
        vd);
    // Not greater (unordered: true), as !(a > t).
    unsigned mask = static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(_mm256_andnot_ps(sign, r), vt, _CMP_NGT_UQ)));
    while (mask) {
      out.push_back(static_cast<int>(i) + __builtin_ctz(mask));
      mask &= mask - 1;
    }
  }
  indicesInBandPlain(x, y, z, wide, n, nx, ny, nz, d, t, out);
}
#endif

}  // namespace

std::size_t countInBand(const float* x, const float* y, const float* z, std::size_t n, float a, float b, float c, float d, float t,
                        std::size_t best) {
#if BIMLOC_BAND_COUNT_X86
  return hasAvx2() ? countAvx2(x, y, z, n, a, b, c, d, t, best) : countSse2(x, y, z, n, a, b, c, d, t, best);
#else
  (void)best;
  return countInBandPlain(x, y, z, n, a, b, c, d, t);
#endif
}

void indicesInBand(const float* x, const float* y, const float* z, std::size_t n, float nx, float ny, float nz, float d, float t,
                   std::vector<int>& out) {
#if BIMLOC_BAND_COUNT_X86
  if (hasAvx2()) return indicesInBandAvx2(x, y, z, n, nx, ny, nz, d, t, out);
#endif
  indicesInBandPlain(x, y, z, 0, n, nx, ny, nz, d, t, out);
}

std::size_t countInBandPlain(const float* x, const float* y, const float* z, std::size_t n, float a, float b, float c, float d,
                             float t) {
  const std::size_t packed = n & ~std::size_t(3);
  std::size_t count = 0;
  for (std::size_t i = 0; i < packed; ++i) count += inBandPacked(a, b, c, d, t, x[i], y[i], z[i]);
  return count + countTail(x, y, z, packed, n, a, b, c, d, t);
}

void pclPlaneInliers(const float* x, const float* y, const float* z, const int* ids, std::size_t n, float a, float b, float c,
                     float d, double t, std::vector<int>& ids_out, std::vector<double>& distances) {
  for (std::size_t i = 0; i < n; ++i) {
    const float distance = std::abs((a * x[i] + c * z[i]) + (b * y[i] + d));  // d * 1.0f is d
    if (static_cast<double>(distance) < t) ids_out.push_back(ids[i]), distances.push_back(static_cast<double>(distance));
  }
}

}  // namespace bimloc::planes::detail
