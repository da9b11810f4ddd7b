// readIfc: the extraction pipeline of the paper's section "Building Information Extraction":
// storeys (floor information), rooms (IfcSpace), walls as double-sided planes, topology.
#include <bimloc/bim/ifc_reader.hpp>

#include "extraction.hpp"
#include "ifc_file.hpp"
#include "ifc_geometry.hpp"
#include "openings.hpp"
#include "stairs.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <set>
#include <tuple>
#include <unordered_map>

namespace bimloc::bim {
namespace {

using detail::RawModel;
using detail::RawProduct;

double minZ(const RawProduct& p) {
  double z = std::numeric_limits<double>::infinity();
  for (const auto& v : p.mesh.vertices) z = std::min(z, double(v.z()));
  if (p.extrusion) z = std::min(z, p.extrusion->z_min);
  return z;
}

double maxZ(const RawProduct& p) {
  double z = -std::numeric_limits<double>::infinity();
  for (const auto& v : p.mesh.vertices) z = std::max(z, double(v.z()));
  if (p.extrusion) z = std::max(z, p.extrusion->z_max);
  return z;
}

// Index in `storeys` (sorted by elevation) of the product's storey: its spatial container,
// or, outside the spatial tree, the highest storey at or below its base.
int storeyFor(const RawProduct& p, const std::vector<int>& new_index, const std::vector<Storey>& storeys) {
  if (p.storey >= 0) return new_index[static_cast<std::size_t>(p.storey)];
  const double z = minZ(p);
  if (!std::isfinite(z)) return -1;
  int best = 0;
  for (int i = 0; i < static_cast<int>(storeys.size()); ++i)
    if (storeys[static_cast<std::size_t>(i)].elevation_m <= z + 0.1) best = i;
  return best;
}

// The body rebuilt from its extrusion with its openings cut out (openings.hpp: every body
// IFC++ could not mesh, and every one-box body with box openings), else IFC++'s mesh.
const TriangleMesh& bodyMesh(const RawProduct& p, const std::unordered_map<int, TriangleMesh>& rebuilt) {
  static const TriangleMesh none;
  const auto it = rebuilt.find(p.entity_id);
  if (it != rebuilt.end()) return it->second;
  return p.mesh.empty() ? none : p.mesh;
}

bool isSlab(const RawProduct& p) {
  return p.ifc_class == "IfcSlab" || p.ifc_class == "IfcRoof" || p.ifc_class == "IfcCovering";
}

// Everything physical of the storey, plus the floor under it and the ceiling above it
// (slabs that belong to the storey below or above, depending on the authoring tool).
bool isDoor(const RawProduct& p) { return p.ifc_class == "IfcDoor" || p.ifc_class == "IfcDoorStandardCase"; }

void buildStoreyMeshes(const RawModel& raw, const std::vector<int>& new_index, bool door_leaves,
                       const std::unordered_map<int, TriangleMesh>& rebuilt, Building& building) {
  auto& storeys = building.storeys;
  for (std::size_t s = 0; s < storeys.size(); ++s) {
    const double floor = storeys[s].elevation_m;
    double top = s + 1 < storeys.size() ? storeys[s + 1].elevation_m : floor;
    for (const auto& w : storeys[s].walls) top = std::max(top, w.start.z() + w.height_m);
    if (top <= floor) top = floor + 3.0;
    auto& mesh = storeys[s].mesh;
    for (const auto* group : {&raw.walls, &raw.elements}) {
      for (const auto& p : *group) {
        if (!door_leaves && isDoor(p)) continue;
        const int in = storeyFor(p, new_index, storeys);
        const bool own = in == static_cast<int>(s);
        const bool floor_or_ceiling = !own && isSlab(p) && maxZ(p) > floor - 0.6 && minZ(p) < top + 0.6 &&
                                      (std::abs(maxZ(p) - floor) < 0.6 || std::abs(minZ(p) - top) < 0.6);
        if (!own && !floor_or_ceiling) continue;
        MeshPart part{p.global_id, p.name, p.ifc_class, static_cast<std::uint32_t>(mesh.vertices.size()), 0,
                      static_cast<std::uint32_t>(mesh.triangles.size()), 0};
        detail::appendMesh(mesh, bodyMesh(p, rebuilt));
        part.vertex_count = static_cast<std::uint32_t>(mesh.vertices.size()) - part.first_vertex;
        part.triangle_count = static_cast<std::uint32_t>(mesh.triangles.size()) - part.first_triangle;
        storeys[s].mesh_parts.push_back(std::move(part));
      }
    }
  }
}

// The footprint of a wall body as XY polygons: its mesh's triangles seen from above, or its
// extruded profile.
std::vector<Polygon2> footprintShape(const RawProduct& p) {
  std::vector<Polygon2> shape;
  for (const auto& t : p.mesh.triangles) {
    Polygon2 triangle;
    for (const auto v : t) triangle.emplace_back(p.mesh.vertices[v].x(), p.mesh.vertices[v].y());
    if (std::abs(signedArea(triangle)) > 1e-6) shape.push_back(triangle);
  }
  if (shape.empty() && p.extrusion && p.extrusion->footprint.size() >= 3) shape.push_back(p.extrusion->footprint);
  return shape;
}

// A curtain wall and the panels and mullions it is made of (IfcPlate and IfcMember are used
// for other things too, rafters, stringers: cut at a level's probe height, those are small).
bool isCurtainWallPart(const RawProduct& p) {
  return p.ifc_class == "IfcCurtainWall" || p.ifc_class == "IfcPlate" || p.ifc_class == "IfcMember";
}

// A storey with walls and no room (no IfcSpace) gets rooms inferred from its walls; with
// options.infer_rooms every storey does, its IfcSpace rooms dropped. Returns whether it did.
bool inferMissingRooms(Storey& storey, const RoomBounds& bounds, const ExtractOptions& options,
                       std::vector<std::string>& warnings) {
  const std::size_t replaced = options.infer_rooms ? storey.rooms.size() : 0;
  if (!storey.rooms.empty() && !options.infer_rooms) return false;
  if (options.infer_rooms) storey.rooms.clear();
  if (storey.walls.empty()) {  // e.g. a "top of" level: no walls, no rooms, no error
    if (replaced > 0) warnings.push_back("storey '" + storey.name + "': " + std::to_string(replaced) +
                                         " IfcSpace rooms dropped, no walls to infer rooms from");
    return false;
  }
  InferredRooms inferred = inferRooms(storey, options.room_inference, bounds);
  warnings.insert(warnings.end(), inferred.warnings.begin(), inferred.warnings.end());
  storey.rooms = std::move(inferred.rooms);
  return true;
}

}  // namespace

Building readIfc(const std::string& path, const ExtractOptions& options) {
  const detail::PlanText plan = detail::readPlanText(path);
  const RawModel raw = detail::readRawModel(plan, path);
  if (raw.storeys.empty()) throw BimError(path + ": no IfcBuildingStorey: the plan has no storeys");
  if (raw.walls.empty()) throw BimError(path + ": no IfcWall: the plan has no walls");
  const auto t_model = std::chrono::steady_clock::now();

  Building building;
  building.file = path;
  building.schema = raw.schema;
  building.warnings = raw.warnings;
  building.map_origin_in_plan_m = raw.map_origin_in_plan_m;

  // Storeys in height order (paper: floor information extraction).
  std::vector<int> order(raw.storeys.size());
  std::iota(order.begin(), order.end(), 0);
  const std::vector<detail::StoreyLevel> levels = detail::storeyLevels(raw, building.warnings);
  const auto elevation = [&](int i) { return levels[static_cast<std::size_t>(i)].elevation_m; };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return elevation(a) < elevation(b); });
  std::vector<int> new_index(raw.storeys.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto& s = raw.storeys[static_cast<std::size_t>(order[k])];
    new_index[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
    Storey storey;
    storey.id = s.global_id;
    storey.name = s.name;
    storey.elevation_m = elevation(order[k]);
    storey.elevation_source = levels[static_cast<std::size_t>(order[k])].source;
    building.storeys.push_back(storey);
  }

  const auto rebuilt = detail::rebuiltBodies(raw, building.warnings);  // bodies read from extrusions, openings cut
  WallShapes shapes;  // the exact footprints of the walls that are not boxes, for room inference
  std::vector<Eigen::Vector2d> wall_points;
  for (const auto& p : raw.walls)
    if (!p.mesh.empty()) wall_points.emplace_back(p.mesh.vertices.front().x(), p.mesh.vertices.front().y());
    else if (p.extrusion && !p.extrusion->corners.empty()) wall_points.push_back(p.extrusion->corners.front().head<2>());
  const Eigen::Vector2d middle = detail::planMiddle(wall_points);
  for (const auto& p : raw.walls) {
    std::string problem;
    auto wall = detail::wallFromGeometry(p, problem);
    if (wall)
      if (std::string far = detail::farFromPlan(*wall, middle); !far.empty()) wall.reset(), problem = far;
    const int s = storeyFor(p, new_index, building.storeys);
    if (!wall || s < 0) {
      building.warnings.push_back(describeProduct(p) + ": wall skipped: " + (problem.empty() ? "no storey" : problem));
      continue;
    }
    if (!problem.empty()) building.warnings.push_back(describeProduct(p) + ": " + problem);
    if (wall->approximated) shapes[wall->id] = footprintShape(p);
    else
      for (auto& face : wall->faces) face.openings = detail::faceOpenings(face, wall->start.z(), wall->height_m, bodyMesh(p, rebuilt));
    building.storeys[static_cast<std::size_t>(s)].walls.push_back(std::move(*wall));
  }
  if (std::all_of(building.storeys.begin(), building.storeys.end(), [](const Storey& s) { return s.walls.empty(); }))
    throw BimError(path + ": no usable wall: every one of its " + std::to_string(raw.walls.size()) +
                   " IfcWall was skipped (" + building.warnings.back() + ")");
  for (const auto& p : raw.spaces) {
    std::string problem;
    auto room = detail::roomFromGeometry(p, problem);
    if (room)
      if (std::string far = detail::farFromPlan(*room, middle); !far.empty()) room.reset(), problem = far;
    const int s = storeyFor(p, new_index, building.storeys);
    if (!room || s < 0) {
      building.warnings.push_back(describeProduct(p) + ": room skipped: " + (problem.empty() ? "no storey" : problem));
      continue;
    }
    building.storeys[static_cast<std::size_t>(s)].rooms.push_back(std::move(*room));
  }
  // Curtain walls bound rooms, as barriers of each part (a bent one is no wall landmark, and a
  // façade filed under the storey below may stand through this one: Jesse.1.ifc).
  RoomBounds bounds{std::move(shapes), {}, {}};
  for (const auto& p : raw.elements) {
    const int s = storeyFor(p, new_index, building.storeys);
    if (isCurtainWallPart(p))
      bounds.barriers.push_back({p.global_id, p.mesh.empty() && p.extrusion ? detail::prismMesh(*p.extrusion) : p.mesh,
                                 s >= 0 ? building.storeys[static_cast<std::size_t>(s)].id : ""});
  }
  std::vector<std::size_t> replaced(building.storeys.size(), 0);
  std::vector<bool> inferred(building.storeys.size(), false);
  for (std::size_t s = 0; s < building.storeys.size(); ++s) {
    auto& storey = building.storeys[s];
    bounds.other_storeys.clear();
    for (const auto& other : building.storeys)
      if (&other != &storey) bounds.other_storeys.push_back(&other);
    replaced[s] = options.infer_rooms ? storey.rooms.size() : 0;
    inferred[s] = inferMissingRooms(storey, bounds, options, building.warnings);
  }
  const auto dropped = dropRoomsOfLowerStoreys(building.storeys, options.room_inference);
  building.warnings.insert(building.warnings.end(), dropped.begin(), dropped.end());
  // Straight curtain walls are walls too (curtain_walls.cpp), filed under their own storey;
  // added after the room inference, which has their parts as barriers already.
  // Their faces move onto the panels once the rooms are linked to the assembly's box.
  std::vector<std::tuple<std::size_t, std::size_t, std::array<double, 2>>> visible;  // storey, wall, depths
  for (auto& cw : detail::curtainWallsOf(raw, building.warnings)) {
    const int s = storeyFor(cw.body, new_index, building.storeys);
    if (s < 0) continue;
    auto& walls = building.storeys[static_cast<std::size_t>(s)].walls;
    visible.emplace_back(static_cast<std::size_t>(s), walls.size(), cw.visible_depth_m);
    walls.push_back(std::move(cw.wall));
  }
  for (std::size_t s = 0; s < building.storeys.size(); ++s) {
    auto& storey = building.storeys[s];
    if (inferred[s]) {
      const std::string count = std::to_string(storey.rooms.size());
      building.warnings.push_back("storey '" + storey.name + "': " +
                                  (options.infer_rooms ? std::to_string(replaced[s]) + " IfcSpace rooms replaced, " + count
                                                       : "no IfcSpace, " + count) +
                                  " rooms inferred from the walls");
    }
    detail::linkRoomsToWalls(storey, raw.space_boundaries, options);
    for (const auto& room : storey.rooms)
      if (room.walls.empty())
        building.warnings.push_back((room.source == "IfcSpace" ? "IfcSpace " + room.id : "storey '" + storey.name + "': room") +
                                    " '" + room.name + "': no bounding wall found");
  }
  for (const auto& [s, w, depth] : visible) detail::moveFacesToVisibleSurfaces(building.storeys[s].walls[w], depth);
  building.stairs = detail::stairFlightsOf(
      raw, building.storeys, [&](const RawProduct& p) -> const TriangleMesh& { return bodyMesh(p, rebuilt); },
      building.warnings);
  if (options.build_meshes) buildStoreyMeshes(raw, new_index, options.door_leaves, rebuilt, building);
  // Storeys of one name (a site of several buildings, each with its "Ground floor"): the name
  // alone no longer says which; tables and reports label them by index (Building::storeyLabel).
  std::set<std::string> named_alike;  // warned once per name, at its first storey
  for (std::size_t s = 0; s < building.storeys.size(); ++s) {
    const std::string& name = building.storeys[s].name;
    if (!name.empty() && building.storeyLabel(s) != name && named_alike.insert(name).second)
      building.warnings.push_back("storeys named '" + name + "' are several (several buildings?): they are called '" +
                                  building.storeyLabel(s) + "' and so on, and --storey takes that label, the index or the GlobalId");
  }

  building.times.parse_s = raw.parse_s;
  building.times.geometry_s = raw.geometry_s;
  building.times.model_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_model).count();
  return building;
}

}  // namespace bimloc::bim
