// Degrees to radians, for the bench's configuration (scenarios, sites, the base's turns): one
// constant, so that files compiled together (unity batches) do not each define their own.
#pragma once

#include <cmath>

namespace bimloc::sim {

inline constexpr double kDegToRad = M_PI / 180.0;

}  // namespace bimloc::sim
