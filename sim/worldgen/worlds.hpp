// The buildings the project owns, generated rather than drawn: each is a WorldSpec (the
// ground truth) that writeIfc4 turns into the IFC file under worlds/ (see worlds/README.md).
#pragma once

#include "sim/worldgen/world_spec.hpp"

#include <string>
#include <vector>

namespace bimloc::worldgen {

// The project's default world: the repetitive site office, hardest for the localizer.
inline const char* const kDefaultWorld = "site_office";

// "site_office", "apartment", "two_storey", "nebula_room".
std::vector<std::string> worldNames();

// Throws std::invalid_argument listing the valid names for an unknown one.
WorldSpec makeWorld(const std::string& name);

}  // namespace bimloc::worldgen
