// The extraction against the generator: what bim::readIfc gives back from the IFC that
// writeIfc4 made of a WorldSpec must be that spec (storeys, walls and their faces, rooms, their
// footprints and their walls). GoogleTest assertions; used by test_worlds and test_random_worlds.
#pragma once

#include "sim/worldgen/world_spec.hpp"

#include <bimloc/bim/building.hpp>

namespace bimloc::test {

struct SpecTolerance {
  double thickness_m = 1e-6;  // wall thickness
  double axis_m = 0.01;       // wall axis end points
  double face_m = 0.01;       // the face planes' offset d
  double vertex_m = 0.01;     // room footprint corners and centre
  double area_m2 = 1e-4;
};

// Same storeys (elevations), as many walls and rooms per storey, no warning.
void expectStoreysMatch(const worldgen::WorldSpec& spec, const bim::Building& building);
// Every wall found by its GlobalId: thickness, height, axis, and both faces (normal within 0.5
// degree, offset within tolerance, x / y class).
void expectWallsMatch(const worldgen::WorldSpec& spec, const bim::Building& building, const SpecTolerance& tolerance);
// Every room found by its GlobalId: names, footprint corners, area, centre, topology source,
// and exactly the spec's walls, each linked by the face that lies on the footprint.
void expectRoomsMatch(const worldgen::WorldSpec& spec, const bim::Building& building, const SpecTolerance& tolerance);

}  // namespace bimloc::test
