// Rooms as a scenario names them: by name (R101), GlobalId, or long name (Office) when that is
// unique on the storey. Shared by the scenario checks and the planner so both agree.
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <string>

namespace bimloc::sim {

// The room, or nullptr with `problem` set: unknown (listing the storey's rooms) or ambiguous.
const bim::Room* lookUpRoom(const bim::Storey& storey, const std::string& name_or_id, std::string* problem);

// "R101 (Office), R102 (Office), C100 (Corridor)", or "none" for a storey without rooms.
std::string roomList(const bim::Storey& storey);

// The room whose footprint contains p, or nullptr.
const bim::Room* roomAt(const bim::Storey& storey, const Eigen::Vector2d& p);

}  // namespace bimloc::sim
