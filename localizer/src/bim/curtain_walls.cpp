// Curtain walls as wall landmarks.
//
// An IfcCurtainWall is, in IFC4's own words, "an exterior wall of a building which is an
// assembly of components, hung from the edge of the floor/roof structure rather than bearing
// on a floor"; its components (IfcPlate panels, IfcMember mullions and transoms) are its parts
// through IfcRelAggregates, and the curtain wall itself usually has no body of its own
// (SampleHouse4.ifc, Jesse.1.ifc). What a lidar sees of it depends on the glass: opaque panels
// and frames, glass at near-normal incidence, protective film or dust return points from the
// panels' plane; clean glass lets most rays through (the simulator's `site.glass`). Either way
// the only plane there is to see is that of the assembly: the panels and mullions lie within a
// few centimetres of one line. So a straight curtain wall is a wall like any other, its box the
// footprint rectangle of all its parts (its faces the innermost and outermost surfaces of the
// assembly); a bent or curved one (a corner curtain wall) has no single plane and is left out,
// with a warning, rather than approximated by a plane nothing lies in.
#include "extraction.hpp"

#include <unordered_map>

namespace bimloc::bim::detail {

bool isCurtainWall(const RawProduct& p) { return p.ifc_class == "IfcCurtainWall"; }

std::vector<CurtainWall> curtainWallsOf(const RawModel& raw, std::vector<std::string>& warnings) {
  std::unordered_map<int, std::size_t> index;  // entity id -> position in the result
  std::vector<CurtainWall> out;
  for (const auto& p : raw.elements)
    if (isCurtainWall(p)) {
      index[p.entity_id] = out.size();
      CurtainWall cw;
      cw.body = p;  // its own body, if any, then its parts' (below)
      cw.body.extrusion.reset();
      if (p.mesh.empty() && p.extrusion) cw.body.mesh = prismMesh(*p.extrusion);
      out.push_back(std::move(cw));
    }
  for (const auto& p : raw.elements) {
    const auto it = index.find(p.whole_entity_id);
    if (it == index.end() || isCurtainWall(p)) continue;
    appendMesh(out[it->second].body.mesh, p.mesh.empty() && p.extrusion ? prismMesh(*p.extrusion) : p.mesh);
    ++out[it->second].parts;
  }
  std::vector<CurtainWall> usable;
  for (auto& cw : out) {
    std::string problem;
    auto wall = wallFromGeometry(cw.body, problem);
    if (!wall) {
      warnings.push_back(describeProduct(cw.body) + ": curtain wall not used as a wall landmark: " + problem);
      continue;
    }
    if (wall->approximated) {
      const std::string shape = problem.substr(0, problem.find(": faces approximated"));
      warnings.push_back(describeProduct(cw.body) + ": curtain wall not used as a wall landmark: " + shape +
                         ", no single plane");
      continue;
    }
    cw.wall = std::move(*wall);
    usable.push_back(std::move(cw));
  }
  return usable;
}

}  // namespace bimloc::bim::detail
