// The dataset's one clock: simulation seconds plus kDatasetTimeOffsetS, kept as integer
// nanoseconds so that the bag, the TUM files and clouds/index.csv carry the very same stamps.
#pragma once

#include <cstdint>
#include <string>

namespace bimloc::sim {

// Simulation time (s) -> dataset time (ns). Throws std::invalid_argument when the result
// would not be a valid positive ROS time (stamp before -offset, NaN, beyond 2^32 s).
std::uint64_t datasetStampNs(double stamp_s);

// "1000.100000000": seconds with all nine decimals, exact (no double in between).
std::string formatStampS(std::uint64_t stamp_ns);

}  // namespace bimloc::sim
