// The place search's bookkeeping (pf/pose_sets.cpp: flat hash tables, linear time) against its
// definitions written out with sorting and std::map, as hypotheses.cpp had them: the same poses
// in the same order, the same hypotheses kept, over generated lists full of repeats, crowded
// cells, ties and near-duplicates.
#include "pf/pose_sets.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <map>
#include <random>
#include <tuple>
#include <vector>

using bimloc::pf::Particle;
using bimloc::pf::detail::Hypothesis;

namespace {

std::uint64_t bits(double v) {
  std::uint64_t u = 0;
  std::memcpy(&u, &v, sizeof u);
  return u;
}

// The first of each bit-identical (x, y, yaw), in order: by sorting.
std::vector<Particle> repeatsDroppedBySorting(const std::vector<Particle>& poses) {
  std::vector<std::tuple<std::uint64_t, std::uint64_t, std::uint64_t, std::size_t>> keys;
  for (std::size_t k = 0; k < poses.size(); ++k) keys.emplace_back(bits(poses[k].x), bits(poses[k].y), bits(poses[k].yaw), k);
  std::sort(keys.begin(), keys.end());
  std::vector<char> first(poses.size(), 0);
  for (std::size_t k = 0; k < keys.size(); ++k)
    if (k == 0 || std::get<0>(keys[k]) != std::get<0>(keys[k - 1]) || std::get<1>(keys[k]) != std::get<1>(keys[k - 1]) ||
        std::get<2>(keys[k]) != std::get<2>(keys[k - 1]))
      first[std::get<3>(keys[k])] = 1;
  std::vector<Particle> kept;
  for (std::size_t k = 0; k < poses.size(); ++k)
    if (first[k]) kept.push_back(poses[k]);
  return kept;
}

// Votes per cell key (a std::map), then a sort by (-votes, position).
std::vector<Particle> agreedFirstBySorting(const std::vector<Particle>& poses) {
  const auto key = [](const Particle& p) {
    const auto ix = static_cast<std::int64_t>(std::floor(p.x / 0.25)), iy = static_cast<std::int64_t>(std::floor(p.y / 0.25));
    const auto ia = static_cast<std::int64_t>(std::floor(p.yaw / (5.0 * M_PI / 180.0)));
    return (ix * 73856093) ^ (iy * 19349663) ^ (ia * 83492791);
  };
  std::map<std::int64_t, int> votes;
  for (const auto& p : poses) ++votes[key(p)];
  std::vector<std::pair<int, std::size_t>> order;
  for (std::size_t k = 0; k < poses.size(); ++k) order.emplace_back(-votes[key(poses[k])], k);
  std::sort(order.begin(), order.end());
  std::vector<Particle> sorted;
  for (const auto& [v, k] : order) sorted.push_back(poses[k]);
  return sorted;
}

// Each hypothesis against every one kept before it.
std::vector<Hypothesis> distinctByPairs(const std::vector<Hypothesis>& sorted, std::size_t max_count) {
  std::vector<Hypothesis> kept;
  for (const auto& h : sorted) {
    const bool duplicate = std::any_of(kept.begin(), kept.end(), [&](const Hypothesis& o) {
      return (h.x - o.x) * (h.x - o.x) + (h.y - o.y) * (h.y - o.y) < 0.04 &&
             std::abs(bimloc::wrapAngle(h.yaw - o.yaw)) < 5.0 * M_PI / 180.0;
    });
    if (duplicate) continue;
    kept.push_back(h);
    if (kept.size() >= max_count) break;
  }
  return kept;
}

bool same(const Particle& a, const Particle& b) {
  return bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y) && bits(a.yaw) == bits(b.yaw) && a.room == b.room;
}
bool same(const Hypothesis& a, const Hypothesis& b) {
  return bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y) && bits(a.yaw) == bits(b.yaw) && a.room == b.room &&
         bits(a.log_likelihood) == bits(b.log_likelihood) && a.associated == b.associated;
}
template <class T>
void expectSameLists(const std::vector<T>& a, const std::vector<T>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_TRUE(same(a[k], b[k])) << "at " << k;
}

// Poses crowded into a few places (many in one cell, some repeated bit for bit, yaws across
// the wrap), and some spread over a floor of 100 m.
std::vector<Particle> generatedPoses(std::mt19937& rng, std::size_t n) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), coin(0.0, 1.0);
  std::vector<Particle> places(1 + rng() % 12);
  for (auto& c : places) c.x = 50.0 * unit(rng), c.y = 50.0 * unit(rng), c.yaw = M_PI * unit(rng), c.room = int(rng() % 9) - 1;
  std::vector<Particle> poses;
  for (std::size_t k = 0; k < n; ++k) {
    const double pick = coin(rng);
    if (pick < 0.2 && !poses.empty()) {
      poses.push_back(poses[rng() % poses.size()]);  // a repeat
    } else if (pick < 0.8) {
      Particle p = places[rng() % places.size()];
      p.x += 0.3 * unit(rng), p.y += 0.3 * unit(rng), p.yaw = bimloc::wrapAngle(p.yaw + 0.1 * unit(rng));
      poses.push_back(p);
    } else {
      Particle p;
      p.x = 50.0 * unit(rng), p.y = 50.0 * unit(rng), p.yaw = M_PI * unit(rng), p.room = int(rng() % 9) - 1;
      poses.push_back(p);
    }
  }
  return poses;
}

}  // namespace

namespace {

// `change` on generated lists of each size against `reference` on the same list.
template <class Change, class Reference>
void expectAsReference(std::uint32_t seed, std::initializer_list<std::size_t> sizes, Change change, Reference reference) {
  std::mt19937 rng(seed);
  for (const std::size_t n : sizes)
    for (int round = 0; round < 5; ++round) {
      std::vector<Particle> poses = generatedPoses(rng, n);
      const std::vector<Particle> expected = reference(poses);
      change(poses);
      expectSameLists(poses, expected);
    }
}

}  // namespace

TEST(PoseSets, RepeatsDroppedAsBySorting) {
  expectAsReference(3611, {0, 1, 2, 5, 40, 300, 5000}, bimloc::pf::detail::dropRepeatedPoses, repeatsDroppedBySorting);
}

TEST(PoseSets, MostAgreedFirstAsBySorting) {
  expectAsReference(3612, {0, 1, 3, 50, 700, 20000}, bimloc::pf::detail::mostAgreedFirst, agreedFirstBySorting);
}

TEST(PoseSets, DistinctBestAsByComparingEveryPair) {
  std::mt19937 rng(3613);
  std::uniform_real_distribution<double> score(-40.0, 0.0);
  for (std::size_t n : {0, 1, 4, 60, 900, 4000}) {
    for (std::size_t max_count : {std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(1000)}) {
      std::vector<Hypothesis> sorted;
      for (const auto& p : generatedPoses(rng, n)) sorted.push_back({p.x, p.y, p.yaw, p.room, std::round(score(rng)), int(rng() % 9)});
      std::sort(sorted.begin(), sorted.end(), [](const Hypothesis& a, const Hypothesis& b) {
        return a.log_likelihood != b.log_likelihood ? a.log_likelihood > b.log_likelihood
                                                    : std::tie(a.x, a.y, a.yaw) < std::tie(b.x, b.y, b.yaw);
      });
      expectSameLists(bimloc::pf::detail::distinctBest(sorted, max_count), distinctByPairs(sorted, max_count));
    }
  }
}
