#include "sim/metrics/trajectory_sync.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim {

namespace {

// The index of the stamp nearest to t in the sorted `stamps`, the first one on a tie (numpy's
// argmin): a binary search instead of evo's scan of them all.
std::size_t nearest(const std::vector<double>& stamps, double t) {
  const auto it = std::lower_bound(stamps.begin(), stamps.end(), t);
  auto i = static_cast<std::size_t>(it - stamps.begin());
  if (i == stamps.size()) return i - 1;
  if (i > 0 && std::abs(stamps[i - 1] - t) <= std::abs(stamps[i] - t)) return i - 1;
  return i;
}

}  // namespace

StampPairs associateStamps(const std::vector<double>& first, const std::vector<double>& second, double max_diff_s) {
  StampPairs pairs;
  if (first.empty() || second.empty()) return pairs;
  const bool second_longer = second.size() > first.size();
  const std::vector<double>& shorter = second_longer ? first : second;
  const std::vector<double>& longer = second_longer ? second : first;
  for (std::size_t i = 0; i < shorter.size(); ++i) {
    const std::size_t j = nearest(longer, shorter[i]);
    if (!(std::abs(longer[j] - shorter[i]) <= max_diff_s)) continue;
    pairs.first.push_back(second_longer ? i : j);
    pairs.second.push_back(second_longer ? j : i);
  }
  return pairs;
}

}  // namespace bimloc::sim
