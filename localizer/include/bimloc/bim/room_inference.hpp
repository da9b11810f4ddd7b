// Rooms inferred from a storey's walls, for plans without IfcSpace (many real files have
// walls and no spaces; the particle filter's room factor needs rooms).
//
// The walls' footprints are rasterized, small gaps between walls that don't quite meet are
// closed, the outside of the building is flooded from the grid's border, and the free space
// inside is split into rooms at the doorways (narrow passages) by a marker-based watershed on
// the distance to the walls; each room is polygonized, its edges snapped onto the wall faces
// along them, and too small or too thin regions are dropped (named in the warnings).
#pragma once

#include <bimloc/bim/building.hpp>
#include <bimloc/bim/geometry2d.hpp>

#include <map>
#include <string>
#include <vector>

namespace bimloc::bim {

struct RoomInferenceConfig {
  // Levels: walls starting at the same height (within level_tolerance_m) make a level of the
  // storey when no height has more of them, or when they are at least min_level_walls and
  // min_level_share of the storey's walls (one storey may hold two physical levels, as
  // example.ifc; a gable wall under the roof or a landing's walls are no level). A level's
  // rooms are bounded by the walls that stand at probe_height_m above its floor, the height a
  // walking robot's body and lidar move at: curbs are not room boundaries, nor walls hanging
  // from above; a level none of whose own walls stands there (only curbs) has no rooms.
  double level_tolerance_m = 0.3;
  std::size_t min_level_walls = 3;
  double min_level_share = 0.25;
  double probe_height_m = 0.5;
  double ceiling_tolerance_m = 0.3;  // for walls of other storeys, see RoomBounds
  double cell_m = 0.05;  // raster resolution
  // The raster never exceeds this many cells: a larger storey is rasterized coarser (warned).
  std::size_t max_cells = 6'000'000;
  // Gaps between walls up to this width are closed (walls that don't quite meet at corners).
  double max_gap_m = 0.2;
  // Passages up to this width split rooms: the doorways where a plan splits a wall at a door.
  // (Wall boxes are full rectangles, so doors hosted by a wall are closed already.)
  double door_width_m = 1.0;
  // The outside is where a disk of this diameter rolling in from far away reaches: gaps in
  // the building's envelope narrower than this keep it out (entrances modelled as a gap,
  // windows of a curtain wall at the probe height, a split-level's stair opening).
  double envelope_gap_m = 3.0;
  // ... but a region open to the outside along more than this fraction of its boundary is
  // outside (the space between two wings closer than envelope_gap_m).
  double max_open_fraction = 0.5;
  // Regions smaller than this, or where no disk of this diameter fits, are not rooms.
  double min_area_m2 = 1.0;
  double min_width_m = 0.6;
  // A footprint edge is moved onto a wall face parallel to it (within the angle) and this close.
  double snap_distance_m = 0.12;
  double snap_angle_deg = 10.0;
  double max_overlap_of_lower = 0.5;  // see dropRoomsOfLowerStoreys
};

struct InferredRooms {
  std::vector<Room> rooms;            // source = "inferred", walls linked by geometric adjacency
  std::vector<std::string> warnings;  // regions dropped, raster coarsened
};

// The exact footprint of walls that are not straight boxes (curved, L-shaped), by wall id:
// polygons in world XY (e.g. the body's triangles) rasterized instead of the wall's box.
using WallShapes = std::map<std::string, std::vector<Polygon2>>;

// An element that bounds rooms without being a wall landmark: a curtain wall's panels and
// mullions (a glass façade that a lidar mostly sees through, and nobody walks through). Its
// body is cut at each level's probe height; what it cuts there bounds rooms.
struct RoomBarrier {
  std::string id;
  TriangleMesh mesh;     // world frame
  std::string storey_id;  // the storey it is filed under; one of another storey counts where it
                          // rises through a level's floor (a façade filed under the storey below)
};

// What bounds a storey's rooms beyond its own walls' boxes (readIfc fills it from the plan).
struct RoomBounds {
  WallShapes shapes;
  std::vector<RoomBarrier> barriers;  // curtain walls, cut at each level's probe height
  // The building's other storeys. A wall of theirs that stands in none of their own levels
  // (a wall on a landing, filed under the storey below) bounds this storey's rooms where it
  // stands at a level's probe height and reaches its ceiling (the median top of the level's
  // own walls). Walls that do bound rooms of their own storey are left to it: a split-level's
  // walls would otherwise stand through the next half-level too.
  std::vector<const Storey*> other_storeys;
};

// Rooms of one storey from its walls alone: the storey's own rooms are ignored. A storey
// without walls has no rooms. Deterministic: the same storey gives the same rooms.
InferredRooms inferRooms(const Storey& storey, const RoomInferenceConfig& config = {}, const RoomBounds& bounds = {});

// An inferred room lying mostly (more than max_overlap_of_lower of its area) within rooms of
// a lower storey whose walls stand through its probe height is that storey's space seen
// again, not a floor of its own (Jesse.1's "top of" reference levels hold the façade walls):
// such rooms are dropped; returns the warnings naming them. Storeys in height order.
std::vector<std::string> dropRoomsOfLowerStoreys(std::vector<Storey>& storeys, const RoomInferenceConfig& config = {});

}  // namespace bimloc::bim
