// Room association (paper, "Room Association"): the walls a keyframe sees around it form a
// room (two pairs of opposite walls) or a corridor (one pair); when it matches a plan room
// (its centre within room_match_distance_m; a corridor also by the robot standing in the
// room), a new plane among those walls is a plan wall that plane association missed, e.g.
// one built too far off its plan position for the gate: the duplicate is merged into it.
#pragma once

#include "graph.hpp"

namespace bimloc::sgraph::detail {

// Returns the number of new planes merged into plan walls (also counted in the result).
int associateRooms(Graph& g, const Keyframe& kf, const SGraphConfig& config, SGraphResult& result);

// Moves plan wall node `to` (its face k) onto new plane `from`, points every measurement of the
// window at it and retires the new plane.
void mergeInto(Graph& g, int from, int to, int k, SGraphResult& result);

}  // namespace bimloc::sgraph::detail
