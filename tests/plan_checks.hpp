// Independent checks of a generated storey, from its spec's geometry alone (walls as boxes,
// doors as openings in them, room footprints), for tests/test_random_worlds.cpp.
#pragma once

#include "sim/worldgen/world_spec.hpp"

#include <string>
#include <vector>

namespace bimloc::test {

// The rooms each door opens into (index into storey.rooms; -1 outside), found by stepping
// 5 cm past both faces of its wall at its centre.
std::vector<std::pair<int, int>> doorRooms(const worldgen::StoreySpec& storey);

// Which rooms a body of radius `radius_m` reaches on foot from room `from`: a 5 cm grid over
// the outline, a cell free when its centre is farther than the radius from every wall box
// outside the door openings and from every door frame (5 cm jambs, as the IFC writer makes
// them), and inside the outline; 4-connected flood fill from a free cell of the start room.
// A room counts as reached when a reached cell lies inside its footprint.
std::vector<bool> roomsReachedOnFoot(const worldgen::StoreySpec& storey, int from, double radius_m);

// For the 180-degree turn and the mirrors x -> -x and y -> -y about the centre of the
// outline's bounding box: how many walls and door openings have no image among them (1 cm).
struct SymmetryCount {
  std::string name;
  int unmatched = 0;
};
std::vector<SymmetryCount> symmetryCounts(const worldgen::StoreySpec& storey);

// The longest run of rooms that are translated copies of each other - same rectangle, doors at
// the same places relative to it - side by side at a constant pitch along x or y.
int longestIdenticalRow(const worldgen::StoreySpec& storey);

}  // namespace bimloc::test
