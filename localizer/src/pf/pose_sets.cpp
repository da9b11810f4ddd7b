#include "pose_sets.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace bimloc::pf::detail {
namespace {

constexpr std::uint32_t kFreeSlot = 0xFFFFFFFFu;

std::uint64_t poseBits(double v) {
  std::uint64_t u = 0;
  std::memcpy(&u, &v, sizeof u);
  return u;
}
// splitmix64's finaliser: the table's slot from a key.
std::uint64_t slotHash(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
// Open addressing, linear probing: a power of two at least twice the entries.
std::size_t slotCount(std::size_t entries) {
  std::size_t size = 16;
  while (size < 2 * entries) size *= 2;
  return size;
}

}  // namespace

void dropRepeatedPoses(std::vector<Particle>& poses) {
  std::vector<std::uint32_t> slots(slotCount(poses.size()), kFreeSlot);
  const std::size_t mask = slots.size() - 1;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const Particle& p = poses[k];
    const std::uint64_t x = poseBits(p.x), y = poseBits(p.y), yaw = poseBits(p.yaw);
    std::size_t slot = slotHash(x ^ slotHash(y ^ slotHash(yaw))) & mask;
    bool repeat = false;
    for (; slots[slot] != kFreeSlot; slot = (slot + 1) & mask) {
      const Particle& q = poses[slots[slot]];  // a kept one, already moved to its place
      if (poseBits(q.x) == x && poseBits(q.y) == y && poseBits(q.yaw) == yaw) {
        repeat = true;
        break;
      }
    }
    if (repeat) continue;
    slots[slot] = static_cast<std::uint32_t>(kept);
    poses[kept++] = p;
  }
  poses.resize(kept);
}

void mostAgreedFirst(std::vector<Particle>& poses) {
  const auto key = [](const Particle& p) {
    const auto ix = static_cast<std::int64_t>(std::floor(p.x / 0.25)), iy = static_cast<std::int64_t>(std::floor(p.y / 0.25));
    const auto ia = static_cast<std::int64_t>(std::floor(p.yaw / (5.0 * M_PI / 180.0)));
    return (ix * 73856093) ^ (iy * 19349663) ^ (ia * 83492791);
  };
  // Each pose's cell, by the cell's number in a table of distinct keys; then the votes.
  std::vector<std::int64_t> keys;
  std::vector<std::uint32_t> slots(slotCount(poses.size()), kFreeSlot), cell_of(poses.size());
  std::vector<std::size_t> votes;
  const std::size_t mask = slots.size() - 1;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const std::int64_t c = key(poses[k]);
    std::size_t slot = slotHash(static_cast<std::uint64_t>(c)) & mask;
    while (slots[slot] != kFreeSlot && keys[slots[slot]] != c) slot = (slot + 1) & mask;
    if (slots[slot] == kFreeSlot) slots[slot] = static_cast<std::uint32_t>(keys.size()), keys.push_back(c), votes.push_back(0);
    cell_of[k] = slots[slot];
    ++votes[slots[slot]];
  }
  // Most votes first, ties in list order: a counting sort by votes, stable.
  std::size_t most = 0;
  for (const std::size_t v : votes) most = std::max(most, v);
  std::vector<std::size_t> start(most + 2, 0);
  for (std::size_t k = 0; k < poses.size(); ++k) ++start[most - votes[cell_of[k]] + 1];
  for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<Particle> sorted(poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) sorted[start[most - votes[cell_of[k]]]++] = poses[k];
  poses.swap(sorted);
}

std::vector<Hypothesis> distinctBest(const std::vector<Hypothesis>& sorted, std::size_t max_count) {
  // The kept ones in a grid of 0.2 m cells (a table of cells, each a chain of its hypotheses):
  // a near-duplicate lies in one of the 3 x 3 cells around.
  std::vector<Hypothesis> kept;
  const std::size_t most = std::min(sorted.size(), std::max<std::size_t>(max_count, 1));
  std::vector<std::int64_t> cell_x, cell_y;
  std::vector<std::uint32_t> slots(slotCount(most), kFreeSlot), head, next;
  const std::size_t mask = slots.size() - 1;
  const auto slotOf = [&](std::int64_t ix, std::int64_t iy) {
    std::size_t slot = slotHash(static_cast<std::uint64_t>(ix) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(iy)) & mask;
    while (slots[slot] != kFreeSlot && (cell_x[slots[slot]] != ix || cell_y[slots[slot]] != iy)) slot = (slot + 1) & mask;
    return slot;
  };
  for (const auto& h : sorted) {
    const auto ix = static_cast<std::int64_t>(std::floor(h.x / 0.2)), iy = static_cast<std::int64_t>(std::floor(h.y / 0.2));
    bool duplicate = false;
    for (std::int64_t dx = -1; dx <= 1 && !duplicate; ++dx)
      for (std::int64_t dy = -1; dy <= 1 && !duplicate; ++dy) {
        const std::size_t slot = slotOf(ix + dx, iy + dy);
        if (slots[slot] == kFreeSlot) continue;
        for (std::uint32_t k = head[slots[slot]]; k != kFreeSlot; k = next[k]) {
          const Hypothesis& o = kept[k];
          if ((h.x - o.x) * (h.x - o.x) + (h.y - o.y) * (h.y - o.y) < 0.04 && std::abs(wrapAngle(h.yaw - o.yaw)) < kHypothesisAngleRad) {
            duplicate = true;
            break;
          }
        }
      }
    if (duplicate) continue;
    const std::size_t slot = slotOf(ix, iy);
    if (slots[slot] == kFreeSlot) {
      slots[slot] = static_cast<std::uint32_t>(head.size());
      cell_x.push_back(ix), cell_y.push_back(iy), head.push_back(kFreeSlot);
    }
    next.push_back(head[slots[slot]]);
    head[slots[slot]] = static_cast<std::uint32_t>(kept.size());
    kept.push_back(h);
    if (kept.size() >= max_count) break;
  }
  return kept;
}

}  // namespace bimloc::pf::detail
