// Where global localization puts particles (ROS amcl's uniformPoseGenerator draws among the
// map's free cells; a map sliced from a plan has no "unknown" cells, so "free" needs a border).
#pragma once

#include "peers/amcl/likelihood_field.hpp"

#include <bimloc/bim/building.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::peers::amcl {

struct FreeSpace {
  std::vector<std::uint32_t> cells;  // grid indices, ascending
  std::vector<std::string> warnings;
};

// The free cells inside the building: inside a room's footprint, or enclosed by the slice (not
// reachable from the map's border without crossing an obstacle), and at least clearance_m from
// every obstacle (the base's half width: no particle stands in a wall or in the gap between
// its two faces). Falls back, with a warning, to every cell that clearance allows when the
// building has no inside, and to the whole grid when nothing is clear.
FreeSpace freeSpace(const LikelihoodField& field, const bim::Storey& storey, double clearance_m);

}  // namespace bimloc::peers::amcl
