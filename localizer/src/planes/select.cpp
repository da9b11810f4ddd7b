#include "select.hpp"

#include <algorithm>
#include <array>
#include <cstring>

namespace bimloc::planes::detail {
namespace {

// Below this many candidates, the last byte positions are not worth a histogram each.
constexpr std::size_t kSmallSet = 32;

// The highest byte position (a shift: 56, 48, ... 0) where the keys' bits differ, -8 when all
// are equal: `differ` is the or of the keys xor their and.
int highestDifferingByte(std::uint64_t differ) {
  int shift = 56;
  while (shift >= 0 && ((differ >> shift) & 0xffu) == 0) shift -= 8;
  return shift;
}

}  // namespace

double kthSmallest(const std::vector<double>& values, std::size_t k, std::vector<std::uint64_t>& scratch) {
  const std::size_t n = values.size();
  scratch.resize(n);
  // +0 and the positive doubles up to +inf: 0 .. 0x7ff0000000000000. A sign bit (a negative, or
  // -0, which compares equal to +0 yet has other bits) or a NaN: nth_element's own answer.
  constexpr std::uint64_t kInfinity = 0x7ff0000000000000ull;
  bool plain = true;
  std::uint64_t any = 0, all = ~0ull;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t bits;
    std::memcpy(&bits, &values[i], sizeof bits);
    scratch[i] = bits;
    plain = plain && bits <= kInfinity;
    any |= bits, all &= bits;
  }
  if (!plain) {
    std::vector<double> copy = values;
    std::nth_element(copy.begin(), copy.begin() + static_cast<std::ptrdiff_t>(k), copy.end());
    return copy[k];
  }
  // Most significant byte first: count the candidates per value of this byte, keep those of
  // the byte that holds rank k, and go on. Bytes every candidate shares are passed over (the
  // residuals' exponents are mostly one or two: counted, each would be one counter
  // incremented at every key, a chain of dependent stores), and four interleaved counts per
  // byte value keep the increments of neighbouring keys apart.
  std::size_t size = n, rank = k;
  int shift = highestDifferingByte(any ^ all);
  while (shift >= 0 && size > kSmallSet) {
    std::array<std::array<std::uint32_t, 256>, 4> counts{};
    std::size_t i = 0;
    for (; i + 4 <= size; i += 4)
      for (std::size_t lane = 0; lane < 4; ++lane) ++counts[lane][(scratch[i + lane] >> shift) & 0xffu];
    for (; i < size; ++i) ++counts[0][(scratch[i] >> shift) & 0xffu];
    std::size_t digit = 0;
    for (;; ++digit) {
      const std::size_t count = std::size_t(counts[0][digit]) + counts[1][digit] + counts[2][digit] + counts[3][digit];
      if (rank < count) break;
      rank -= count;
    }
    std::size_t kept = 0;
    any = 0, all = ~0ull;
    for (i = 0; i < size; ++i)
      if (((scratch[i] >> shift) & 0xffu) == digit) {
        scratch[kept++] = scratch[i];
        any |= scratch[i], all &= scratch[i];
      }
    size = kept;
    shift = highestDifferingByte((any ^ all) & ((shift == 0 ? 0ull : (~0ull >> (64 - shift)))));
  }
  if (shift >= 0)  // else the candidates left are all equal
    std::nth_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(rank), scratch.begin() + static_cast<std::ptrdiff_t>(size));
  double value;
  std::memcpy(&value, &scratch[rank], sizeof value);
  return value;
}

}  // namespace bimloc::planes::detail
