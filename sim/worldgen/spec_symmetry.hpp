// How far a storey is from symmetric in its walls and doorways: what a lidar can tell apart.
#pragma once

#include "sim/worldgen/world_spec.hpp"

#include <string>
#include <vector>

namespace bimloc::worldgen {

// For one symmetry about the centre of the outline's bounding box: the walls and the door
// openings whose image is no wall / opening of the storey (boxes compared within 1 cm).
struct SymmetryMismatch {
  std::string symmetry;  // "180 deg turn", "mirror x" (x -> -x), "mirror y"
  int walls = 0;
  int doors = 0;
  int total() const { return walls + doors; }
};

// The three symmetries, in that order.
std::vector<SymmetryMismatch> symmetryMismatches(const StoreySpec& storey);

}  // namespace bimloc::worldgen
