// The colour of a particle's weight: viridis (perceptually uniform, readable in grey print).
#pragma once

#include <array>
#include <cstdint>

namespace bimloc::sim::render {

// t in [0, 1] (clamped; NaN gives 0): dark purple at 0, yellow at 1.
std::array<std::uint8_t, 3> viridis(double t);

}  // namespace bimloc::sim::render
