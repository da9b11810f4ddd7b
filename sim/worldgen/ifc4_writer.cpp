#include "sim/worldgen/ifc4_writer.hpp"

#include "sim/worldgen/ifc4_stairs.hpp"
#include "sim/worldgen/ifc_items.hpp"
#include "sim/worldgen/spec_check.hpp"
#include "sim/worldgen/step_file.hpp"

#include <cstdint>

namespace bimloc::worldgen {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using step::real;
using step::ref;
using step::refs;
using step::str;
using namespace ifc;  // the geometric items

constexpr const char* kTimestamp = "2026-01-01T00:00:00";
// The opening box reaches this far past both wall faces and below the floor, so that the
// reader's boolean subtraction never has to cut coplanar faces.
constexpr double kOpeningOverlap_m = 0.05;
// The door body is its frame (jambs and head lining the opening), not a closed leaf, so
// the doorway stays open to the simulated lidar and robot.
constexpr double kDoorLining_m = 0.05;

std::uint64_t fnv1a(const std::string& text, std::uint64_t basis) {
  std::uint64_t h = basis;
  for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

std::uint64_t splitmix(std::uint64_t z) {  // spreads FNV's weak high bits over all 64
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::string seedOf(const WorldSpec& spec, const char* kind, std::size_t storey,
                   std::size_t index) {
  return spec.name + "/" + kind + "/" + std::to_string(storey) + "/" + std::to_string(index);
}

// The file being written, with the shared items, and the world it describes.
struct Writer : ifc::ItemWriter {
  const WorldSpec* spec = nullptr;

  std::string id(const char* kind, std::size_t storey, std::size_t index) const {
    return str(globalId(seedOf(*spec, kind, storey, index)));
  }
};

struct WallIds {
  int wall = 0;
  int placement = 0;
};

// Local x along the axis, local y to its left, z up: the body is the rectangle
// [0, length] × [-t/2, t/2] extruded up the wall height.
WallIds writeWall(Writer& w, const WallSpec& wall, std::size_t s, std::size_t i,
                  int storey_placement) {
  const Vector2d along = wall.end - wall.start;
  const double length = along.norm();
  const Vector3d x(along.x() / length, along.y() / length, 0.0);
  const int placement = localPlacement(
      w, storey_placement, axes(w, Vector3d(wall.start.x(), wall.start.y(), 0.0),
                                Vector3d::UnitZ(), x));
  const int axis_curve = polyline(w, {Vector2d::Zero(), Vector2d(length, 0.0)}, false);
  const int axis_rep = representation(w, w.axis_context, "Axis", "Curve2D", axis_curve);
  const int profile = rectangleProfile(w, Vector2d(length / 2, 0.0), length, wall.thickness_m);
  const int solid = extrusion(w, profile, w.origin_axes, wall.height_m);
  const int body_rep = representation(w, w.body_context, "Body", "SweptSolid", solid);
  const int shape = w.file.add("IFCPRODUCTDEFINITIONSHAPE",
                               {step::unset(), step::unset(), refs({axis_rep, body_rep})});
  const int id = w.file.add("IFCWALL", root(w.id("wall", s, i), wall.name) +
                                           std::vector<std::string>{
                                               step::unset(), ref(placement), ref(shape),
                                               str(wall.name), ".STANDARD."});
  return {id, placement};
}

// The opening (a box through the wall, voiding it) and the door filling it; returns the door.
int writeDoor(Writer& w, const DoorSpec& door, const WallSpec& wall, const WallIds& wall_ids,
              std::size_t s, std::size_t i) {
  const int opening_placement =
      localPlacement(w, wall_ids.placement, translation(w, Vector3d(door.offset_m, 0.0, 0.0)));
  const int opening_profile = rectangleProfile(w, Vector2d::Zero(), door.width_m,
                                               wall.thickness_m + 2 * kOpeningOverlap_m);
  const int opening_solid =
      extrusion(w, opening_profile, translation(w, Vector3d(0.0, 0.0, -kOpeningOverlap_m)),
                door.height_m + kOpeningOverlap_m);
  const std::string name = wall.name + " door " + std::to_string(i);
  const int opening = w.file.add(
      "IFCOPENINGELEMENT", root(w.id("opening", s, i), name) +
                               std::vector<std::string>{step::unset(), ref(opening_placement),
                                                        ref(bodyShape(w, opening_solid)),
                                                        step::unset(), ".OPENING."});
  w.file.add("IFCRELVOIDSELEMENT",
             root(w.id("voids", s, i), {}) + std::vector<std::string>{ref(wall_ids.wall),
                                                                      ref(opening)});

  // Frame profile in the wall plane (x along the wall, y up), an upside-down U.
  const double hw = door.width_m / 2, h = door.height_m, l = kDoorLining_m;
  const std::vector<Vector2d> frame = {{-hw, 0.0}, {-hw + l, 0.0}, {-hw + l, h - l},
                                       {hw - l, h - l}, {hw - l, 0.0}, {hw, 0.0},
                                       {hw, h}, {-hw, h}};
  // Profile plane = the wall plane through the face at +t/2, extruded through the wall.
  const int frame_position = axes(w, Vector3d(0.0, wall.thickness_m / 2, 0.0),
                                  -Vector3d::UnitY(), Vector3d::UnitX());
  const int frame_solid = extrusion(w, polygonProfile(w, frame), frame_position,
                                    wall.thickness_m);
  const int door_placement = localPlacement(w, opening_placement, w.origin_axes);
  const int door_id = w.file.add(
      "IFCDOOR", root(w.id("door", s, i), name) +
                     std::vector<std::string>{step::unset(), ref(door_placement),
                                              ref(bodyShape(w, frame_solid)), step::unset(),
                                              real(door.height_m), real(door.width_m),
                                              ".DOOR.", ".SINGLE_SWING_LEFT.", step::unset()});
  w.file.add("IFCRELFILLSELEMENT", root(w.id("fills", s, i), {}) +
                                       std::vector<std::string>{ref(opening), ref(door_id)});
  return door_id;
}

// A slab whose body is `outline` extruded from z_bottom up `thickness` (storey frame).
int writeSlab(Writer& w, const std::vector<Vector2d>& outline, double z_bottom,
              double thickness, const std::string& name, const char* type, int storey_placement,
              const std::string& quoted_id, int* placement_out = nullptr) {
  const int solid = extrusion(w, polygonProfile(w, outline),
                              translation(w, Vector3d(0.0, 0.0, z_bottom)), thickness);
  const int placement = localPlacement(w, storey_placement, w.origin_axes);
  if (placement_out) *placement_out = placement;
  return w.file.add("IFCSLAB", root(quoted_id, name) +
                                   std::vector<std::string>{step::unset(), ref(placement),
                                                            ref(bodyShape(w, solid)),
                                                            step::unset(), type});
}

int writeSpace(Writer& w, const RoomSpec& room, double height, std::size_t s, std::size_t i,
               int storey_placement) {
  const int solid = extrusion(w, polygonProfile(w, room.footprint), w.origin_axes, height);
  const int placement = localPlacement(w, storey_placement, w.origin_axes);
  return w.file.add("IFCSPACE", root(w.id("space", s, i), room.name) +
                                    std::vector<std::string>{
                                        step::unset(), ref(placement), ref(bodyShape(w, solid)),
                                        str(room.long_name), ".ELEMENT.", ".INTERNAL.",
                                        step::unset()});
}

// One storey with everything in it; returns the IfcBuildingStorey.
int writeStorey(Writer& w, std::size_t s, int building_placement) {
  const WorldSpec& spec = *w.spec;
  const StoreySpec& storey = spec.storeys[s];
  const double clear = clearHeight(spec, s);
  const int placement = localPlacement(w, building_placement,
                                       translation(w, Vector3d(0.0, 0.0, storey.elevation_m)));
  const int storey_id = w.file.add(
      "IFCBUILDINGSTOREY", root(w.id("storey", s, 0), storey.name) +
                               std::vector<std::string>{step::unset(), ref(placement),
                                                        step::unset(), step::unset(),
                                                        ".ELEMENT.", real(storey.elevation_m)});
  std::vector<int> contained;
  std::vector<WallIds> walls;
  for (std::size_t i = 0; i < storey.walls.size(); ++i) {
    walls.push_back(writeWall(w, storey.walls[i], s, i, placement));
    contained.push_back(walls.back().wall);
  }
  for (std::size_t i = 0; i < storey.doors.size(); ++i) {
    const DoorSpec& door = storey.doors[i];
    contained.push_back(writeDoor(w, door, storey.walls[door.wall], walls[door.wall], s, i));
  }
  int floor_placement = 0;
  const int floor_slab = writeSlab(w, storey.outline, -storey.slab_thickness_m,
                                   storey.slab_thickness_m, storey.name + " floor slab", ".FLOOR.",
                                   placement, w.id("floor", s, 0), &floor_placement);
  contained.push_back(floor_slab);
  const ifc::IdFor id_for = [&w, s](const char* kind, std::size_t index) { return w.id(kind, s, index); };
  for (std::size_t i = 0; i < storey.floor_openings.size(); ++i) {
    writeSlabOpening(w, floor_slab, floor_placement, storey.floor_openings[i], -storey.slab_thickness_m,
                     storey.slab_thickness_m, storey.name + " floor slab stair void " + std::to_string(i), i,
                     id_for);
  }
  for (std::size_t i = 0; i < storey.stairs.size(); ++i) {
    contained.push_back(writeStair(w, storey.stairs[i], i, placement, id_for));
  }
  if (s + 1 == spec.storeys.size()) {
    contained.push_back(writeSlab(w, storey.outline, storey.height_m - spec.roof_thickness_m,
                                  spec.roof_thickness_m, "Roof slab", ".ROOF.", placement,
                                  w.id("roof", s, 0)));
  }
  w.file.add("IFCRELCONTAINEDINSPATIALSTRUCTURE",
             root(w.id("contains", s, 0), {}) +
                 std::vector<std::string>{refs(contained), ref(storey_id)});

  std::vector<int> spaces;
  for (std::size_t i = 0; i < storey.rooms.size(); ++i) {
    spaces.push_back(writeSpace(w, storey.rooms[i], clear, s, i, placement));
  }
  if (!spaces.empty()) {
    w.file.add("IFCRELAGGREGATES", root(w.id("storey-spaces", s, 0), {}) +
                                       std::vector<std::string>{ref(storey_id), refs(spaces)});
  }
  if (spec.space_boundaries) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < storey.rooms.size(); ++i) {
      for (int wall : storey.rooms[i].walls) {
        const char* side = storey.walls[wall].exterior ? ".EXTERNAL." : ".INTERNAL.";
        w.file.add("IFCRELSPACEBOUNDARY",
                   root(w.id("boundary", s, n++), {}) +
                       std::vector<std::string>{ref(spaces[i]), ref(walls[wall].wall),
                                                step::unset(), ".PHYSICAL.", side});
      }
    }
  }
  return storey_id;
}

// Units and representation contexts; returns the IfcProject.
int writeProject(Writer& w) {
  const WorldSpec& spec = *w.spec;
  std::vector<int> units;
  const char* const kUnits[][2] = {{"LENGTHUNIT", "METRE"},
                                   {"AREAUNIT", "SQUARE_METRE"},
                                   {"VOLUMEUNIT", "CUBIC_METRE"},
                                   {"PLANEANGLEUNIT", "RADIAN"}};
  for (const auto& unit : kUnits) {
    units.push_back(w.file.add("IFCSIUNIT", {step::derived(), step::enumeration(unit[0]),
                                             step::unset(), step::enumeration(unit[1])}));
  }
  const int unit_assignment = w.file.add("IFCUNITASSIGNMENT", {refs(units)});
  const int north = w.file.add("IFCDIRECTION", {step::reals({0.0, 1.0})});
  const int context = w.file.add("IFCGEOMETRICREPRESENTATIONCONTEXT",
                                 {step::unset(), str("Model"), step::integer(3), real(1e-5),
                                  ref(w.origin_axes), ref(north)});
  auto sub = [&](const char* identifier, const char* view) {
    return w.file.add("IFCGEOMETRICREPRESENTATIONSUBCONTEXT",
                      {str(identifier), str("Model"), "*", "*", "*", "*", ref(context),
                       step::unset(), view, step::unset()});
  };
  w.body_context = sub("Body", ".MODEL_VIEW.");
  w.axis_context = sub("Axis", ".GRAPH_VIEW.");
  return w.file.add("IFCPROJECT", root(w.id("project", 0, 0), spec.name, spec.description) +
                                      std::vector<std::string>{
                                          step::unset(), step::unset(), step::unset(),
                                          refs({context}), ref(unit_assignment)});
}

}  // namespace

std::string globalId(const std::string& seed) {
  static const char* const kAlphabet =
      "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_$";
  const std::uint64_t hi = splitmix(fnv1a(seed, 0xcbf29ce484222325ULL));
  const std::uint64_t lo = splitmix(fnv1a(seed, 0x84222325cbf29ce4ULL) ^ hi);
  auto bit = [&](int k) { return k >= 64 ? (hi >> (k - 64)) & 1U : (lo >> k) & 1U; };
  // 128 bits: 2 in the first character (hence 0-3), then 21 characters of 6 bits.
  std::string id(1, kAlphabet[(hi >> 62) & 3U]);
  for (int c = 0; c < 21; ++c) {
    unsigned value = 0;
    for (int k = 125 - 6 * c; k > 119 - 6 * c; --k) value = (value << 1) | bit(k);
    id += kAlphabet[value];
  }
  return id;
}

std::string storeyGlobalId(const WorldSpec& spec, std::size_t storey) {
  return globalId(seedOf(spec, "storey", storey, 0));
}

std::string wallGlobalId(const WorldSpec& spec, std::size_t storey, std::size_t wall) {
  return globalId(seedOf(spec, "wall", storey, wall));
}

std::string spaceGlobalId(const WorldSpec& spec, std::size_t storey, std::size_t room) {
  return globalId(seedOf(spec, "space", storey, room));
}

std::string writeIfc4(const WorldSpec& spec) {
  checkWorldSpec(spec);
  Writer w;
  w.spec = &spec;
  w.dir_z = direction(w, Vector3d::UnitZ());
  w.dir_x = direction(w, Vector3d::UnitX());
  w.origin_axes = translation(w, Vector3d::Zero());
  const int project = writeProject(w);

  const int site_placement = localPlacement(w, 0, w.origin_axes);
  const int site = w.file.add("IFCSITE", root(w.id("site", 0, 0), "Site") +
                                             std::vector<std::string>{
                                                 step::unset(), ref(site_placement),
                                                 step::unset(), step::unset(), ".ELEMENT.",
                                                 "$", "$", "$", "$", "$"});
  const int building_placement = localPlacement(w, site_placement, w.origin_axes);
  const int building = w.file.add(
      "IFCBUILDING", root(w.id("building", 0, 0), spec.name, spec.description) +
                         std::vector<std::string>{step::unset(), ref(building_placement),
                                                  step::unset(), step::unset(), ".ELEMENT.",
                                                  "$", "$", "$"});
  std::vector<int> storeys;
  for (std::size_t s = 0; s < spec.storeys.size(); ++s) {
    storeys.push_back(writeStorey(w, s, building_placement));
  }
  w.file.add("IFCRELAGGREGATES", root(w.id("project-site", 0, 0), {}) +
                                     std::vector<std::string>{ref(project), refs({site})});
  w.file.add("IFCRELAGGREGATES", root(w.id("site-building", 0, 0), {}) +
                                     std::vector<std::string>{ref(site), refs({building})});
  w.file.add("IFCRELAGGREGATES", root(w.id("building-storeys", 0, 0), {}) +
                                     std::vector<std::string>{ref(building), refs(storeys)});
  return w.file.text(spec.name + ".ifc", kTimestamp, "IFC4");
}

}  // namespace bimloc::worldgen
