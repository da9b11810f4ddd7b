// A random floor stacked into a building of several storeys joined by a stair core
// (random_world.hpp): the stairwell found on the floor, a half-turn stair fitted into it on every
// storey but the top one, a void in every floor slab above the ground floor where the flights
// rise through it. The storeys are the same floor: the same walls, rooms and doors, except that
// the doors in exterior walls (entrances) are on the ground floor only.
#pragma once

#include "sim/worldgen/plan_grid.hpp"
#include "sim/worldgen/stair_layout.hpp"

#include <optional>
#include <string>

namespace bimloc::worldgen {

// The well of room `room` of a built floor: its clear rectangle seen from its one door.
// nullopt when the room is not a rectangle or has no door, or not exactly one.
std::optional<StairWell> stairWellOf(const PlanGrid::Result& floor, int room);

// Where the first flight goes up: on the side of the well's door (a walker goes straight on).
bool firstFlightOnLowSide(const PlanGrid::Result& floor, int room, const StairWell& well);

// The first room of `use` (an office) that a stair climbing `storey_height_m` fits in; -1 none.
int roomForStair(const PlanGrid::Result& floor, const std::string& use, double storey_height_m);

// `storeys` copies of spec.storeys[0] (storey k: "Floor k", walls and rooms named "Sk-..." from
// k = 1 on), each `height_m` above the last, walls up to their ceiling, the stair in `well` from
// each storey to the next. One storey: spec unchanged.
void stackStoreys(WorldSpec& spec, int storeys, const StairWell& well, bool first_on_low_side);

}  // namespace bimloc::worldgen
