// Where a robot that climbed while the localizer searched can be: at the end of a flight that
// arrives on the storeys it climbed to (the plan's stairs say where a flight arrives, issue
// 31). The rooms there are the new search's prior rooms, in place of the whole storey.
#pragma once

#include <bimloc/bim/building.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace bimloc::storeys {

// The ids (names where a room has no id) of the rooms of `storeys` within reach_m of the end of a flight arriving there (its
// top when `up`, its bottom when not). Empty when some such end has no room within reach (a
// landing the plan's rooms do not cover: the prior would leave out where the robot is) or no
// flight arrives there (the search then covers the whole storeys, as without stairs).
std::vector<std::string> landingRooms(const bim::Building& building, const std::vector<std::size_t>& storeys, bool up, double reach_m);

}  // namespace bimloc::storeys
