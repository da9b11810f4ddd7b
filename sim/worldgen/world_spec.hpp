// A generated building, as plain data: what the IFC4 writer emits and, at the same time,
// the ground truth the extraction tests compare the reader's output with. Everything is
// exact by construction, so keep it simple: straight box walls, polygon rooms, no mitres.
// Lengths in metres; x/y in the storey's plan frame, which is the world frame W (the site
// and the building sit at the origin); z of an element is relative to its storey.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace bimloc::worldgen {

// Body = exactly the rectangle start→end ± thickness/2, extruded from the storey elevation
// up height_m. Its two faces are the axis offset by ±thickness/2; the ends are square.
struct WallSpec {
  std::string name;  // unique in the world
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d end = Eigen::Vector2d::Zero();
  double thickness_m = 0.0;
  double height_m = 0.0;
  bool exterior = false;  // part of the building envelope (.EXTERNAL. space boundaries)
};

// A door: an IfcOpeningElement voiding the wall from the floor up to height_m, filled by an
// IfcDoor. height_m stays below the wall's height, the opening inside the wall's length.
struct DoorSpec {
  int wall = -1;          // index into StoreySpec::walls
  double offset_m = 0.0;  // centre of the opening along the wall axis, from WallSpec::start
  double width_m = 0.0;
  double height_m = 0.0;
};

struct RoomSpec {
  std::string name;       // IfcSpace Name, unique in the world, plain ASCII
  std::string long_name;  // IfcSpace LongName
  // The clear interior, counter-clockwise: every edge lies exactly on a face of one of
  // `walls` (but the open ones). The IfcSpace body is this polygon extruded from the floor to
  // the ceiling.
  std::vector<Eigen::Vector2d> footprint;
  std::vector<int> walls;  // indices into StoreySpec::walls of the walls bounding the room
  // Edges (by index: footprint[e] to footprint[e + 1]) on no wall: the room open there, to
  // another room or outside (a plan may draw a space so: open_house).
  std::vector<int> open_edges;
};

// A straight flight of steps (IfcStairFlight): `risers` risers of riser_m and risers - 1 treads
// of going_m; the last riser is the front of the landing or floor it arrives on. The run line
// starts at the first riser, in the middle of the flight's width, and goes along `direction`.
struct StairFlightSpec {
  std::string name;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // unit, axis-aligned
  double z_m = 0.0;  // floor (or landing) the first riser stands on, relative to the storey
  double width_m = 0.0;
  int risers = 0;
  double riser_m = 0.0, going_m = 0.0;
  int treads() const { return risers - 1; }
  double run_m() const { return treads() * going_m; }
  double rise_m() const { return risers * riser_m; }
};

// A landing between flights (IfcSlab .LANDING.): `outline` (CCW) from top_z_m - thickness_m
// up to top_z_m, relative to the storey.
struct LandingSpec {
  std::string name;
  std::vector<Eigen::Vector2d> outline;
  double top_z_m = 0.0, thickness_m = 0.0;
};

// A stair from its storey's floor up to the next storey's (IfcStair decomposed into flights
// and landings): its flights' rises add up to the storey height.
struct StairSpec {
  std::string name;
  std::vector<StairFlightSpec> flights;  // in walking order, upwards
  std::vector<LandingSpec> landings;
};

struct StoreySpec {
  std::string name;
  double elevation_m = 0.0;       // top of the floor slab, world z
  double height_m = 0.0;          // floor to next floor (top of slab to top of slab)
  double slab_thickness_m = 0.0;  // floor slab, hanging below elevation_m
  // The building footprint at this storey (outer faces of the exterior walls), CCW:
  // the floor slab's outline and, on the top storey, the roof slab's.
  std::vector<Eigen::Vector2d> outline;
  std::vector<WallSpec> walls;
  std::vector<DoorSpec> doors;
  std::vector<RoomSpec> rooms;
  std::vector<StairSpec> stairs;  // stairs going up from this storey to the next
  // Voids in this storey's floor slab (CCW polygons): where a flight from below rises through.
  std::vector<std::vector<Eigen::Vector2d>> floor_openings;
};

struct WorldSpec {
  std::string name;  // file stem, e.g. "site_office"
  std::string description;
  std::vector<StoreySpec> storeys;  // in height order
  double roof_thickness_m = 0.0;    // roof slab, its top at the top storey's elevation + height
  bool space_boundaries = false;    // write IfcRelSpaceBoundary room->wall relations or not
};

// Floor to underside of the slab above (the next storey's floor slab or the roof): the height
// of the walls and of the spaces of storey `index`.
inline double clearHeight(const WorldSpec& world, std::size_t index) {
  const StoreySpec& storey = world.storeys.at(index);
  const double above = index + 1 < world.storeys.size()
                           ? world.storeys[index + 1].slab_thickness_m
                           : world.roof_thickness_m;
  return storey.height_m - above;
}

// Deterministic 22-character IFC GlobalId (IFC base64 alphabet 0-9A-Za-z_$, first character
// 0-3) from a 128-bit hash of `seed`: the same seed always gives the same id.
std::string globalId(const std::string& seed);

}  // namespace bimloc::worldgen
