#include "sim/ros2/crc32.hpp"

#ifdef BIMLOC_HAVE_ISAL
#include <isa-l/crc.h>
#if defined(__x86_64__)
#include <immintrin.h>
#endif
#else
#include <zlib.h>

#include <algorithm>
#include <limits>
#endif

namespace bimloc::sim::ros2 {

#ifdef BIMLOC_HAVE_ISAL

namespace {

#if defined(__x86_64__)
// ISA-L 2.30's AVX-512 CRC (VPCLMULQDQ on zmm registers) returns without VZEROUPPER: the
// registers' upper halves stay dirty, and every SSE instruction after it on that thread pays
// for them. Measured on this project's AMD EPYC (Zen 4): a loop of sin, acos and products
// (the de-skew's kind of code) ran 2.4x slower on the thread after one CRC of 4 MiB, and the
// whole bag read 1.45x. So the upper halves are cleared after each call, as the ABI expects.
__attribute__((target("avx"))) void clearUpperHalves() { _mm256_zeroupper(); }
const bool kHasAvx = __builtin_cpu_supports("avx");
#endif

}  // namespace

// crc32_gzip_refl takes and returns the CRC in zlib's convention (the XORs applied inside), so
// it chains exactly as zlib's crc32 does; its length is 64-bit.
std::uint32_t crc32Update(std::uint32_t crc, const std::uint8_t* data, std::size_t n) {
  if (n == 0) return crc;  // (zlib's convention; no pointer is read)
  crc = crc32_gzip_refl(crc, data, n);
#if defined(__x86_64__)
  if (kHasAvx) clearUpperHalves();
#endif
  return crc;
}

const char* crc32Implementation() { return "isa-l"; }

#else

std::uint32_t crc32Update(std::uint32_t crc, const std::uint8_t* data, std::size_t n) {
  while (n > 0) {  // zlib takes a uInt length
    const uInt step = static_cast<uInt>(std::min<std::size_t>(n, std::numeric_limits<uInt>::max()));
    crc = static_cast<std::uint32_t>(::crc32(crc, data, step));
    data += step, n -= step;
  }
  return crc;
}

const char* crc32Implementation() { return "zlib"; }

#endif

}  // namespace bimloc::sim::ros2
