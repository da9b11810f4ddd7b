// Openings (doors, windows, recesses) cut out of the bodies we rebuild from their extrusions.
// IFC++ subtracts an element's IfcOpeningElements from the meshes it makes itself; where it
// makes none (ExampleHOM's walls over IfcIndexedPolyCurve profiles) the body is our prism,
// and without its openings a storey mesh has walls where the plan has doorways.
// Only the storey meshes change: a wall's faces (its planes) are those of the uncut box.
#pragma once

#include "raw_model.hpp"

#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace bimloc::bim::detail {

struct OpeningCut {
  TriangleMesh mesh;
  std::size_t cut = 0;                                      // openings subtracted
  std::vector<std::pair<std::size_t, std::string>> not_cut;  // index into the openings, why
};

// `body` minus `openings`, exactly, when the body is a vertical box (a rectangular footprint
// extruded along z) and each opening a box whose edges run along the body's length, thickness
// and height: the cells between the boxes' planes that lie in no opening, bounded by their
// faces towards empty cells (a closed mesh, with the reveals of each opening). Openings that
// are not such boxes, or miss the body, are listed in not_cut; with none cut, the mesh is
// prismMesh(body).
OpeningCut cutOpenings(const Extrusion& body, const std::vector<Extrusion>& openings);

// By entity id, with its openings cut out: the mesh of every wall and element whose body is
// read from its extrusion (no IFC++ mesh; every opening it could not subtract is named in
// `warnings`, with the element it belongs to), and of every element with openings whose body
// is one box extrusion and whose openings are all boxes along it (RawProduct::sole_body):
// IFC++'s own cut of those changes from run to run on some plans. The others keep IFC++'s.
std::unordered_map<int, TriangleMesh> rebuiltBodies(const RawModel& raw, std::vector<std::string>& warnings);

}  // namespace bimloc::bim::detail
