#include "select.hpp"

#include <algorithm>
#include <array>
#include <cstring>

namespace bimloc::planes::detail {
namespace {

// Below this many candidates, the last byte positions are not worth a histogram each.
constexpr std::size_t kSmallSet = 32;

}  // namespace

double kthSmallest(const std::vector<double>& values, std::size_t k, std::vector<std::uint64_t>& scratch) {
  const std::size_t n = values.size();
  scratch.resize(n);
  // +0 and the positive doubles up to +inf: 0 .. 0x7ff0000000000000. A sign bit (a negative, or
  // -0, which compares equal to +0 yet has other bits) or a NaN: nth_element's own answer.
  constexpr std::uint64_t kInfinity = 0x7ff0000000000000ull;
  bool plain = true;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t bits;
    std::memcpy(&bits, &values[i], sizeof bits);
    scratch[i] = bits;
    plain = plain && bits <= kInfinity;
  }
  if (!plain) {
    std::vector<double> copy = values;
    std::nth_element(copy.begin(), copy.begin() + static_cast<std::ptrdiff_t>(k), copy.end());
    return copy[k];
  }
  // Most significant byte first: count the candidates per value of this byte, keep those of
  // the byte that holds rank k (all candidates share the bytes above it), and go on.
  std::size_t size = n, rank = k;
  for (int shift = 56; shift >= 0 && size > kSmallSet; shift -= 8) {
    std::array<std::uint32_t, 256> count{};
    for (std::size_t i = 0; i < size; ++i) ++count[(scratch[i] >> shift) & 0xffu];
    std::size_t digit = 0;
    while (rank >= count[digit]) rank -= count[digit++];
    if (count[digit] == size) continue;  // every candidate has this byte: nothing to drop
    std::size_t kept = 0;
    for (std::size_t i = 0; i < size; ++i)
      if (((scratch[i] >> shift) & 0xffu) == digit) scratch[kept++] = scratch[i];
    size = kept;
  }
  std::nth_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(rank), scratch.begin() + static_cast<std::ptrdiff_t>(size));
  double value;
  std::memcpy(&value, &scratch[rank], sizeof value);
  return value;
}

}  // namespace bimloc::planes::detail
