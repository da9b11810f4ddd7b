// Issue 28, Speed (h28speed10): two helpers that must give the very bits of what they replace.
// The median of refinePlane (planes/select.hpp), by radix selection on the bits of non-negative
// doubles, against std::nth_element on the same values; and a grid's x / cell as a
// multiplication (pf/cell_scale.hpp), against the division, on every power-of-two cell and on
// cells that are not (where it must divide).
#include "planes/select.hpp"
#include "pf/cell_scale.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using bimloc::pf::detail::CellScale;
using bimloc::planes::detail::kthSmallest;

namespace {

std::uint64_t bitsOf(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

double byNthElement(std::vector<double> v, std::size_t k) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

TEST(ExactSelect, IsNthElementsValueOnResidualsOfEverySpreadAndSize) {
  // Residuals as refinePlane makes them (|r| of a wall's returns: millimetres to decimetres,
  // with a far tail), values repeated (voxel centroids, a quantised range), zeros, +inf, denormals
  // and spreads over one exponent or many; every size 1..200, then larger; every rank for small.
  std::mt19937 rng(2810);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::uint64_t> scratch;
  for (int trial = 0; trial < 600; ++trial) {
    const std::size_t n = trial < 200 ? std::size_t(trial + 1) : std::size_t(200 + (trial * 37) % 6000);
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) {
      switch ((trial + i) % 7) {
        case 0: v[i] = std::abs(noise(rng)); break;
        case 1: v[i] = std::abs(noise(rng)) * (unit(rng) < 0.1 ? 100.0 : 1.0); break;
        case 2: v[i] = std::round(unit(rng) * 20.0) * 0.005; break;  // many equal values
        case 3: v[i] = trial % 5 == 0 ? 0.0 : 1.0 + unit(rng); break;  // one exponent
        case 4: v[i] = std::ldexp(unit(rng), -1074 + static_cast<int>(unit(rng) * 60.0)); break;  // denormals
        case 5: v[i] = trial % 11 == 0 ? std::numeric_limits<double>::infinity() : std::abs(noise(rng)); break;
        default: v[i] = std::abs(noise(rng)) * 1e-3;
      }
    }
    const std::vector<double> before = v;
    const std::vector<std::size_t> ranks = n <= 64 ? [&] {
      std::vector<std::size_t> all(n);
      for (std::size_t k = 0; k < n; ++k) all[k] = k;
      return all;
    }()
                                                   : std::vector<std::size_t>{0, n / 2, n - 1, n / 3, (n * 9) / 10};
    for (const std::size_t k : ranks)
      ASSERT_EQ(bitsOf(kthSmallest(v, k, scratch)), bitsOf(byNthElement(v, k))) << "trial " << trial << " n " << n << " k " << k;
    ASSERT_EQ(v, before);  // the values are left as they were
  }
}

TEST(ExactSelect, FallsBackToNthElementOnNegativesNaNsAndNegativeZero) {
  // Outside what the bits can order (a sign bit, a NaN), the answer is nth_element's own.
  std::vector<std::uint64_t> scratch;
  const std::vector<double> mixed{0.3, -0.2, 0.1, -0.0, 0.0, 2.0, -7.5, 0.25};
  for (std::size_t k = 0; k < mixed.size(); ++k) EXPECT_EQ(bitsOf(kthSmallest(mixed, k, scratch)), bitsOf(byNthElement(mixed, k))) << k;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> with_nan{0.3, nan, 0.1, 0.2};
  for (std::size_t k = 0; k < with_nan.size(); ++k)
    EXPECT_EQ(bitsOf(kthSmallest(with_nan, k, scratch)), bitsOf(byNthElement(with_nan, k))) << k;
}

TEST(CellScale, MultipliesOnlyWhereTheDivisionGivesTheSameBits) {
  // Coordinates as a storey gives them (metres off an origin, signed, tiny and huge), divided by
  // power-of-two cells (where the multiplication is used) and by others (where it must divide):
  // the bits of x / cell every time.
  std::mt19937 rng(1028);
  std::uniform_real_distribution<double> metres(-500.0, 500.0), unit(0.0, 1.0);
  std::vector<double> xs{0.0, -0.0, 1e-300, -1e-310, 5e-324, 1e300, -1e308, 0.5, 1.0 - 1e-16};
  for (int i = 0; i < 20000; ++i) xs.push_back(i % 3 == 0 ? metres(rng) : std::ldexp(unit(rng) - 0.5, static_cast<int>(unit(rng) * 40) - 20));
  for (const double cell : {1.0, 0.5, 0.25, 2.0, 4.0, 0.125, std::ldexp(1.0, -1020), std::ldexp(1.0, 1000), 0.3, 0.1, 0.7072, 1.5, 3.0}) {
    const CellScale per_cell(cell);
    for (const double x : xs) ASSERT_EQ(bitsOf(per_cell(x)), bitsOf(x / cell)) << "x " << x << " cell " << cell;
  }
}
