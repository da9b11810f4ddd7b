// Association of two trajectories by timestamp, as evo does it
// (evo.core.sync.associate_trajectories / matching_time_indices): every stamp of the
// trajectory with fewer poses (the second one on a tie) takes the nearest stamp of the other
// (the earlier on a tie), kept when they differ by at most max_diff seconds. A stamp of the
// longer one may so be taken twice, as in evo.
#pragma once

#include <cstddef>
#include <vector>

namespace bimloc::sim {

struct StampPairs {
  std::vector<std::size_t> first, second;  // indices into each trajectory, by the shorter one's order
};

// Stamps strictly increasing (readTum's). max_diff_s >= 0.
StampPairs associateStamps(const std::vector<double>& first, const std::vector<double>& second, double max_diff_s);

}  // namespace bimloc::sim
