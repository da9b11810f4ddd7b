// The IFC4 writer's stairs and slab voids (ifc4_writer.cpp), written the way authoring tools
// export them: an IfcStair without a body of its own, decomposed (IfcRelAggregates) into its
// IfcStairFlights - NumberOfRisers, NumberOfTreads, RiserHeight, TreadLength, a walking line
// ('Axis', Curve2D) and a swept body of the steps ('Body', SweptSolid) - and its landings
// (IfcSlab .LANDING.); and IfcOpeningElements voiding (IfcRelVoidsElement) a floor slab where a
// flight from the storey below rises through it.
#pragma once

#include "sim/worldgen/ifc_items.hpp"
#include "sim/worldgen/world_spec.hpp"

#include <cstddef>
#include <functional>
#include <string>

namespace bimloc::worldgen::ifc {

// The quoted GlobalId of element `kind` number `index` of the storey being written.
using IdFor = std::function<std::string(const char* kind, std::size_t index)>;

// Stair number `index` of the storey and its parts, placed in the storey; returns the IfcStair
// (the one element of it the storey contains).
int writeStair(ItemWriter& w, const StairSpec& stair, std::size_t index, int storey_placement, const IdFor& id);

// Void number `index` in `slab` (placed at `slab_placement`): `outline` through the slab's
// thickness, the slab spanning z_bottom .. z_bottom + thickness in that placement.
void writeSlabOpening(ItemWriter& w, int slab, int slab_placement, const std::vector<Vector2d>& outline, double z_bottom,
                      double thickness, const std::string& name, std::size_t index, const IdFor& id);

}  // namespace bimloc::worldgen::ifc
