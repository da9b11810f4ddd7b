// Writes a WorldSpec as an IFC4 STEP physical file (ISO-10303-21), the kind of plan the
// localizer reads: project, site, building, storeys, walls with axis and swept-solid body,
// floor and roof slabs, doors in openings, spaces, and optionally space boundaries; stairs
// (IfcStair, its IfcStairFlights and landings) and the voids in the slabs they rise through
// (ifc4_stairs.hpp).
#pragma once

#include "sim/worldgen/world_spec.hpp"

#include <cstddef>
#include <string>

namespace bimloc::worldgen {

// The whole file text. Deterministic: the same spec gives byte-identical output (fixed
// header timestamp, GlobalIds hashed from the world, element kind and index).
// Throws std::invalid_argument naming the element of a spec that is not self-consistent
// (bad index, door outside its wall or taller than it, clockwise footprint, ...).
std::string writeIfc4(const WorldSpec& spec);

// The GlobalIds writeIfc4 gives the spec's elements, so that tests can match what the
// reader extracted with the spec element it came from.
std::string storeyGlobalId(const WorldSpec& spec, std::size_t storey);
std::string wallGlobalId(const WorldSpec& spec, std::size_t storey, std::size_t wall);
std::string spaceGlobalId(const WorldSpec& spec, std::size_t storey, std::size_t room);

}  // namespace bimloc::worldgen
