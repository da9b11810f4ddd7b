// When the oracle's test first holds along a run's keyframes (docs/oracle.md, "Checks").
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <optional>

namespace bimloc::sim::oracle {

// The first keyframe >= lowest at which `holds` is true: forwards every stride-th keyframe (and
// the last), then each keyframe after the last check that failed, up to the one that held. Unset
// when no check holds. The first crossing is the decision: Ville's inequality bounds the chance
// that the likelihood ratio EVER crosses the threshold, so stopping there keeps the false-alarm
// rate (docs/oracle.md). A later check may fall back below it without the scans up to here
// having ruled anything less out: over a long run the odometry's drift bends the path that every
// start shares, and a 60 s run's late keyframes can favour a rival (random_office_24000 R005).
inline std::optional<std::size_t> firstCrossing(std::size_t count, std::size_t lowest, std::size_t stride,
                                                const std::function<bool(std::size_t)>& holds) {
  stride = std::max<std::size_t>(stride, 1);
  std::size_t after = lowest;  // the first keyframe after the last check that failed
  for (std::size_t k = lowest; k < count;) {
    if (holds(k)) {
      for (std::size_t j = after; j < k; ++j)
        if (holds(j)) return j;
      return k;
    }
    after = k + 1;
    if (k + 1 == count) break;
    k = std::min(k + stride, count - 1);
  }
  return std::nullopt;
}

}  // namespace bimloc::sim::oracle
