// The oracle's check schedule (sim/oracle/first_crossing.hpp) against a brute force over every
// pattern of passing and failing keyframes up to 12 long:
// - where a run, once decided, stays decided (every pattern false...false true...true), it finds
//   the first keyframe that holds, whatever the stride;
// - in any pattern, what it returns holds, and every keyframe it skipped over lies between two
//   checks that failed: a crossing is missed only when undone within one stride;
// - a run decided early and undone later (the odometry's drift over a long run) is decided at its
//   first crossing, not at the end.
#include "sim/oracle/first_crossing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

using bimloc::sim::oracle::firstCrossing;

namespace {

struct Checked {
  std::optional<std::size_t> first;
  std::set<std::size_t> looked;
};

Checked run(const std::vector<bool>& holds, std::size_t lowest, std::size_t stride) {
  Checked c;
  c.first = firstCrossing(holds.size(), lowest, stride, [&](std::size_t k) {
    c.looked.insert(k);
    return static_cast<bool>(holds.at(k));
  });
  return c;
}

}  // namespace

TEST(FirstCrossing, MonotoneRunsGiveTheFirstKeyframeThatHolds) {
  for (std::size_t n = 1; n <= 12; ++n)
    for (std::size_t from = 0; from <= n; ++from)  // holds from `from` on (n: never)
      for (std::size_t stride = 1; stride <= 5; ++stride)
        for (std::size_t lowest = 0; lowest < n; ++lowest) {
          std::vector<bool> holds(n);
          for (std::size_t k = from; k < n; ++k) holds[k] = true;
          const Checked c = run(holds, lowest, stride);
          const std::size_t expected = std::max(from, lowest);
          if (expected >= n) {
            EXPECT_FALSE(c.first) << n << " " << from << " " << stride;
            EXPECT_TRUE(c.looked.count(n - 1)) << "the last keyframe is always checked";
          } else {
            ASSERT_TRUE(c.first) << n << " " << from << " " << stride;
            EXPECT_EQ(*c.first, expected) << n << " " << from << " " << stride << " " << lowest;
          }
        }
}

TEST(FirstCrossing, AnyPatternGivesAKeyframeThatHoldsAfterChecksThatFailed) {
  for (std::size_t n = 1; n <= 12; ++n)
    for (unsigned bits = 0; bits < (1u << n); ++bits)
      for (std::size_t stride = 1; stride <= 4; ++stride) {
        std::vector<bool> holds(n);
        for (std::size_t k = 0; k < n; ++k) holds[k] = (bits >> k) & 1u;
        const Checked c = run(holds, 0, stride);
        for (std::size_t k : c.looked) ASSERT_LT(k, n);
        if (!c.first) {
          // Nothing held where it looked, and it looked at every stride-th keyframe and the last.
          for (std::size_t k : c.looked) EXPECT_FALSE(holds[k]);
          for (std::size_t k = 0; k < n; k += stride) EXPECT_TRUE(c.looked.count(k));
          EXPECT_TRUE(c.looked.count(n - 1));
          continue;
        }
        EXPECT_TRUE(holds[*c.first]);
        // Every keyframe before the answer that it looked at failed; the ones it did not look
        // at lie strictly between two that it did.
        for (std::size_t k = 0; k < *c.first; ++k) {
          if (c.looked.count(k)) {
            EXPECT_FALSE(holds[k]) << bits << " " << stride << " " << k;
            continue;
          }
          const bool before = std::any_of(c.looked.begin(), c.looked.end(), [&](std::size_t j) { return j < k; });
          EXPECT_TRUE(before) << bits << " " << stride << " " << k;
        }
        // With stride 1 it is the brute force's first keyframe that holds.
        if (stride == 1) {
          std::size_t brute = 0;
          while (!holds[brute]) ++brute;
          EXPECT_EQ(*c.first, brute);
        }
      }
}

TEST(FirstCrossing, ADecisionUndoneLaterStandsAtItsFirstCrossing) {
  // Decided at keyframe 9 (between the checks at 8 and 12), undone from keyframe 30 on: the
  // scans up to 9 ruled every rival out, whatever the later ones say.
  std::vector<bool> holds(40, false);
  for (std::size_t k = 9; k < 30; ++k) holds[k] = true;
  const Checked c = run(holds, 0, 4);
  ASSERT_TRUE(c.first);
  EXPECT_EQ(*c.first, 9u);
  EXPECT_FALSE(c.looked.count(39)) << "it stops at the first crossing";
}
