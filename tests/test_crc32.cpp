// The MCAP chunks' CRC-32 (sim/ros2/crc32.hpp: Intel ISA-L's where the build found it, else
// zlib's) against two independent implementations: zlib's crc32 (the one MCAP's specification
// names) and the bit-by-bit definition of the reflected polynomial 0xEDB88320. On generated
// buffers of every length from 0 to 300 and a spread of lengths up to about 70 000 (odd ones,
// and around the 16/32/64-byte folds of a carry-less multiply implementation), at every
// alignment from 0 to 15, whole and chained over random cuts. Fixed seeds.
#include "sim/ros2/crc32.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <random>
#include <vector>

#if defined(__x86_64__)
#include <cpuid.h>
#endif

namespace {

using bimloc::sim::ros2::crc32Update;

std::uint32_t zlibCrc(std::uint32_t crc, const std::uint8_t* data, std::size_t n) {
  return static_cast<std::uint32_t>(::crc32(crc, data, static_cast<uInt>(n)));
}

// The definition: reflected input and output, initial and final XOR 0xFFFFFFFF.
std::uint32_t bitwiseCrc(std::uint32_t crc, const std::uint8_t* data, std::size_t n) {
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int b = 0; b < 8; ++b) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::vector<std::size_t> testLengths() {
  std::vector<std::size_t> lengths;
  for (std::size_t n = 0; n <= 300; ++n) lengths.push_back(n);
  for (std::size_t fold : {512u, 1024u, 4096u, 16384u, 65536u})
    for (std::size_t d : {0u, 1u, 15u, 16u, 17u, 31u, 32u, 33u, 63u, 64u, 65u}) lengths.push_back(fold + d), lengths.push_back(fold - d);
  std::mt19937 rng(2911);
  std::uniform_int_distribution<std::size_t> any(301, 70001);
  for (int i = 0; i < 60; ++i) lengths.push_back(any(rng) | 1u);  // odd ones
  lengths.push_back(70001);
  return lengths;
}

std::vector<std::uint8_t> randomBytes(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<std::uint8_t> b(n);
  for (auto& x : b) x = static_cast<std::uint8_t>(rng());
  return b;
}

TEST(Crc32, KnownValues) {
  const std::uint8_t digits[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(crc32Update(0, digits, 9), 0xCBF43926u);  // the CRC-32 check value
  EXPECT_EQ(crc32Update(0, nullptr, 0), 0u);
  EXPECT_EQ(crc32Update(0x12345678u, digits, 0), 0x12345678u);
  std::printf("CRC-32 by %s\n", bimloc::sim::ros2::crc32Implementation());
}

TEST(Crc32, MatchesZlibAtEveryLengthAndAlignment) {
  const std::vector<std::size_t> lengths = testLengths();
  const std::vector<std::uint8_t> bytes = randomBytes(70001 + 16, 29);
  std::size_t checked = 0;
  for (const std::size_t n : lengths)
    for (std::size_t align = 0; align < 16; ++align) {
      const std::uint8_t* p = bytes.data() + align;
      ASSERT_EQ(crc32Update(0, p, n), zlibCrc(0, p, n)) << n << " bytes at alignment " << align;
      ++checked;
    }
  EXPECT_GT(checked, 7000u);
}

TEST(Crc32, MatchesTheBitwiseDefinition) {
  const std::vector<std::uint8_t> bytes = randomBytes(4096 + 16, 31);
  for (std::size_t n = 0; n <= 4096; n += (n < 300 ? 1 : 97))
    for (std::size_t align : {0u, 1u, 3u, 8u, 13u})
      ASSERT_EQ(crc32Update(0, bytes.data() + align, n), bitwiseCrc(0, bytes.data() + align, n)) << n << " at " << align;
  // Bytes that are all ones and all zeros, where a wrong XOR convention shows.
  for (const std::uint8_t fill : {std::uint8_t{0}, std::uint8_t{0xFF}}) {
    const std::vector<std::uint8_t> same(1000, fill);
    EXPECT_EQ(crc32Update(0, same.data(), same.size()), bitwiseCrc(0, same.data(), same.size()));
  }
}

TEST(Crc32, ChainsOverAnyCuts) {
  std::mt19937 rng(28);
  const std::vector<std::uint8_t> bytes = randomBytes(70001 + 16, 30);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t align = rng() % 16;
    const std::size_t n = std::uniform_int_distribution<std::size_t>(0, 70001)(rng);
    const std::uint8_t* p = bytes.data() + align;
    std::uint32_t chained = 0;
    std::size_t at = 0;
    while (at < n) {  // pieces of 0 to ~9000 bytes, odd lengths and empty ones among them
      const std::size_t piece = std::min<std::size_t>(n - at, rng() % 9001);
      chained = crc32Update(chained, p + at, piece);
      at += piece;
    }
    ASSERT_EQ(chained, zlibCrc(0, p, n)) << n << " bytes at alignment " << align << ", trial " << trial;
    // And continuing from a CRC that is not 0: as zlib continues from it.
    const std::uint32_t seed = static_cast<std::uint32_t>(rng());
    ASSERT_EQ(crc32Update(seed, p, n), zlibCrc(seed, p, n));
  }
}

// The vector registers' state a CRC leaves behind: ISA-L's AVX-512 code left their upper halves
// dirty, which made every SSE instruction after it on the thread slow (the bag read 1.45x; see
// crc32.cpp). XGETBV(1) says which state components are in use: bit 2 the YMM upper halves,
// bit 6 the ZMM upper halves of registers 0-15. A processor may report a component in use
// that is not (never the reverse), so a CPU whose XGETBV(1) reports them after a VZEROUPPER of
// its own is skipped.
#if defined(__x86_64__)
__attribute__((target("avx"))) void zeroUpperForTest() { __builtin_ia32_vzeroupper(); }
std::uint64_t statesInUse() {
  std::uint32_t lo = 0, hi = 0;
  __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(1));
  return (std::uint64_t{hi} << 32) | lo;
}
#endif

TEST(Crc32, LeavesNoDirtyUpperVectorHalves) {
#if defined(__x86_64__)
  unsigned a = 0, b = 0, c = 0, d = 0;
  if (!__get_cpuid_count(0xD, 1, &a, &b, &c, &d) || !(a & (1u << 2)) || !__builtin_cpu_supports("avx"))
    GTEST_SKIP() << "this CPU has no XGETBV(1) or no AVX";
  constexpr std::uint64_t kUpperHalves = (1u << 2) | (1u << 6);
  zeroUpperForTest();
  if (statesInUse() & kUpperHalves) GTEST_SKIP() << "this CPU reports the upper halves in use even when clear";
  const std::vector<std::uint8_t> bytes = randomBytes(4u << 20, 32);
  for (const std::size_t n : {std::size_t{100}, std::size_t{4096}, bytes.size()}) {
    (void)crc32Update(0, bytes.data(), n);
    EXPECT_EQ(statesInUse() & kUpperHalves, 0u) << "after a CRC of " << n << " bytes by " << bimloc::sim::ros2::crc32Implementation();
  }
#else
  GTEST_SKIP() << "x86-64 only";
#endif
}

}  // namespace
