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
//
// The box's faces are the assembly's outermost surfaces, often the mullions' (Jesse.1's
// curtain walls: 150 mm mullions, the panels' room side 100 mm behind their fronts). A lidar
// sees mostly the panels, and a plane fitted to the scan lies on them, so each face is moved
// back onto the surface with the most area facing its way (WallFace is "one side of a wall,
// as the lidar sees it"). The room topology is linked to the box first: rooms are drawn to
// the assembly's lines, not to its panels.
#include "extraction.hpp"

#include <algorithm>
#include <cmath>
#include <map>
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
    cw.visible_depth_m = visibleSurfaceDepths(cw.body.mesh, cw.wall);
    usable.push_back(std::move(cw));
  }
  return usable;
}

std::array<double, 2> visibleSurfaceDepths(const TriangleMesh& mesh, const Wall& wall) {
  constexpr double kBin_m = 0.01;                         // surfaces closer than this are one
  const double kFacing = std::cos(10.0 * M_PI / 180.0);   // a triangle facing the face's way
  std::array<double, 2> depth{0.0, 0.0};
  for (std::size_t k = 0; k < 2; ++k) {
    const Plane& plane = wall.faces[k].plane;
    std::map<long, std::pair<double, double>> bins;  // depth bin -> (area, area * depth)
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                            c = mesh.vertices[t[2]].cast<double>();
      const Eigen::Vector3d cross = (b - a).cross(c - a);
      const double area = 0.5 * cross.norm();
      if (!(area > 1e-9) || cross.dot(plane.n) < kFacing * 2.0 * area) continue;
      const double d = -plane.signedDistance((a + b + c) / 3.0);  // behind the face: > 0
      if (!std::isfinite(d) || d < -kBin_m || d > wall.thickness_m + kBin_m) continue;
      auto& bin = bins[std::lround(d / kBin_m)];
      bin.first += area, bin.second += area * d;
    }
    // The bin of most area (the nearest to the face on a tie), refined to its area-weighted
    // mean with its neighbours.
    double best = 0.0;
    long at = 0;
    for (const auto& [key, v] : bins)
      if (v.first > best * (1.0 + 1e-9)) best = v.first, at = key;
    if (best <= 0.0) continue;
    double area = 0.0, moment = 0.0;
    for (long key = at - 1; key <= at + 1; ++key)
      if (const auto it = bins.find(key); it != bins.end()) area += it->second.first, moment += it->second.second;
    depth[k] = std::clamp(moment / area, 0.0, wall.thickness_m);
  }
  return depth;
}

void moveFacesToVisibleSurfaces(Wall& wall, const std::array<double, 2>& depth_m) {
  for (std::size_t k = 0; k < 2; ++k) {
    WallFace& f = wall.faces[k];
    const Eigen::Vector3d back = -depth_m[k] * Eigen::Vector3d(f.plane.n.x(), f.plane.n.y(), 0.0);
    f.start += back, f.end += back;
    f.plane.d = -f.plane.n.dot(f.start);
  }
}

}  // namespace bimloc::bim::detail
