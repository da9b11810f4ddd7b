// The building model extracted from an architectural plan: the top two layers of a
// Situational Graph (paper, section "Building Information Extraction"): storeys, rooms
// (topological layer) and walls as double-sided planes (metric-semantic layer).
// All lengths in metres, in the plan's world frame W (z up), whatever the file's unit.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::bim {

// A plane n·p + d = 0 with |n| = 1.
struct Plane {
  Eigen::Vector3d n = Eigen::Vector3d::UnitX();
  double d = 0.0;

  double signedDistance(const Eigen::Vector3d& p) const { return n.dot(p) + d; }
};

// The paper's semantic class of a vertical wall: which normal component dominates.
enum class WallAxis { X, Y };
const char* toString(WallAxis axis);

// A hole in a wall face (a window, a door, a recess): a rectangle on the face, along it from
// the face's start and in world z. Seen through it are a window's glass, a door leaf, the
// room beyond: planes parallel to the face but not on it.
struct FaceOpening {
  double along_min_m = 0, along_max_m = 0;
  double z_min_m = 0, z_max_m = 0;
};

// One side of a wall, as the lidar sees it. The normal points out of the wall.
struct WallFace {
  Plane plane;
  WallAxis axis = WallAxis::X;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  // face's first corner at the wall's base
  Eigen::Vector3d end = Eigen::Vector3d::Zero();    // face's last corner at the wall's base
  std::vector<FaceOpening> openings;  // where the wall's body has no surface on this face
  double length_m() const { return (end - start).norm(); }
  // Whether the rectangle [along_min, along_max] x [z_min, z_max] lies inside the face's holes:
  // the openings grown by margin_m on every side (see insideOpening).
  bool inOpening(double along_min_m, double along_max_m, double z_min_m, double z_max_m, double margin_m) const;
};

// Whether the rectangle lies inside `openings` grown by margin_m on every side: the grown
// openings that span its heights cover [along_min, along_max] together. Openings side by side
// count as one hole: a window and the glazed door beside it, 0.1 m of wall between them (the
// Duplex's living rooms), hold one pane of glass 6 m wide.
inline bool insideOpening(const std::vector<FaceOpening>& openings, double along_min_m, double along_max_m,
                          double z_min_m, double z_max_m, double margin_m) {
  if (!(along_max_m >= along_min_m)) return false;
  // How far from along_min the covered stretch reaches: each pass extends it by an opening
  // that starts within it and ends beyond it (at most one pass per opening).
  double reach = along_min_m;
  for (bool grew = true; grew && reach < along_max_m;) {
    grew = false;
    for (const auto& o : openings)
      if (z_min_m >= o.z_min_m - margin_m && z_max_m <= o.z_max_m + margin_m && o.along_min_m - margin_m <= reach &&
          o.along_max_m + margin_m > reach)
        reach = o.along_max_m + margin_m, grew = true;
  }
  return reach >= along_max_m;
}

inline bool WallFace::inOpening(double along_min_m, double along_max_m, double z_min_m, double z_max_m,
                                double margin_m) const {
  return insideOpening(openings, along_min_m, along_max_m, z_min_m, z_max_m, margin_m);
}

struct Wall {
  std::string id;        // IFC GlobalId
  std::string name;
  std::string ifc_type;  // IfcWall, IfcWallStandardCase, ...
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  // axis segment at the wall's base
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  double height_m = 0.0;
  double thickness_m = 0.0;
  std::array<WallFace, 2> faces;  // faces[0] on the left of start→end, faces[1] on the right
  std::string source;             // "mesh" or "profile": where the geometry came from
  bool approximated = false;      // not a straight box: faces are a best fit (see warnings)

  double length_m() const { return (end - start).norm(); }
};

// A face of a wall that bounds a room, seen from inside the room.
struct RoomWall {
  std::string wall_id;
  int face = -1;  // index into Wall::faces of the face looking into the room, -1 if unknown
};

struct Room {
  std::string id;  // IFC GlobalId of the IfcSpace; "<storey id>/R<n>" for an inferred room
  std::string name;
  std::string long_name;
  std::string source = "IfcSpace";  // or "inferred": from the storey's walls (room_inference.hpp)
  std::vector<Eigen::Vector2d> footprint;  // counter-clockwise polygon in world XY
  double area_m2 = 0.0;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // area centroid of the footprint
  double floor_z = 0.0;                              // world z of the floor of the space
  double height_m = 0.0;
  std::vector<RoomWall> walls;  // walls bounding the room
  std::string topology_source;  // "IfcRelSpaceBoundary" or "geometry"
};

struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  bool empty() const { return triangles.empty(); }
};

// One physical element's share of a storey mesh: its vertices and triangles are contiguous
// there (the simulator moves, drops or re-materials single elements to make a site differ
// from its plan). Only plans read from IFC have them; a mesh file has none.
struct MeshPart {
  std::string id;         // IFC GlobalId
  std::string name;
  std::string ifc_class;  // IfcWall, IfcDoor, IfcWindow, IfcSlab, ...
  std::uint32_t first_vertex = 0, vertex_count = 0;
  std::uint32_t first_triangle = 0, triangle_count = 0;
};

struct Storey {
  std::string id;  // IFC GlobalId
  std::string name;
  double elevation_m = 0.0;
  std::string elevation_source;  // "Elevation", "placement" or "none" (0 m: neither gave a height)
  std::vector<Room> rooms;
  std::vector<Wall> walls;
  TriangleMesh mesh;  // every physical element, floor below and ceiling above; no spaces
  std::vector<MeshPart> mesh_parts;  // the elements `mesh` is made of, in mesh order

  const Wall* findWall(const std::string& wall_id) const;
  const Room* findRoom(const std::string& name_or_id) const;
  // The first room (in this order) whose footprint holds p, or null: where a pose is.
  const Room* roomAt(const Eigen::Vector2d& p) const;
  std::size_t wallPlaneCount() const { return 2 * walls.size(); }
};

// A flight of steps or a ramp, linking the storeys its ends stand on (issue 31): an
// IfcStairFlight / IfcRampFlight, or a whole IfcStair / IfcRamp that the file does not
// decompose. The run line goes up, from the bottom step's nosing line to the top one's, at the
// flight's middle, in world coordinates; its z values are the floors (or landings) there.
struct StairFlight {
  std::string id;        // IFC GlobalId of the flight (of the stair when not decomposed)
  std::string name;
  std::string ifc_type;  // IfcStairFlight, IfcStair, IfcRampFlight, IfcRamp
  std::string stair_id;  // the IfcStair / IfcRamp it belongs to (its own id when not decomposed)
  Eigen::Vector3d bottom = Eigen::Vector3d::Zero();  // the run line's start, at the bottom floor's z
  Eigen::Vector3d top = Eigen::Vector3d::Zero();     // its end, at the top floor's (or landing's) z
  double width_m = 0.0;
  int risers = 0;               // 0 for a ramp
  double riser_height_m = 0.0;  // rise per step
  double going_m = 0.0;         // tread length (run per step)
  // Indices into Building::storeys of the storeys the bottom and top stand on; -1 for a
  // landing between storeys (the next flight of the same stair goes on from there).
  int bottom_storey = -1, top_storey = -1;
  std::string source;  // "IfcStairFlight attributes", "body", ...: where the numbers came from
  double rise_m() const { return top.z() - bottom.z(); }
  double run_m() const { return (top - bottom).head<2>().norm(); }
};

struct ExtractionTimes {
  double parse_s = 0.0;
  double geometry_s = 0.0;
  double model_s = 0.0;  // storeys, rooms, walls, topology, meshes
};

struct Building {
  std::string file;    // the path it was read from
  std::string schema;  // "IFC2X3" or "IFC4"
  std::vector<Storey> storeys;  // in height order
  std::vector<StairFlight> stairs;  // flights and ramps, in file order (empty: none read)
  std::vector<std::string> warnings;
  ExtractionTimes times;
  // Where the map frame's origin lies in the plan's own coordinates (x y, metres): zero, but
  // for a georeferenced plan whose site lies far from its origin, which bimloc moves near it
  // so that floats hold millimetres (the meshes, the ray caster). A pose in the map frame is
  // at map_origin_in_plan_m + (x, y) in the plan's (REP 105: earth -> map).
  Eigen::Vector2d map_origin_in_plan_m = Eigen::Vector2d::Zero();

  // The storey with that GlobalId, that name or at that index; null when none, and when the
  // name is several storeys' (a site of two buildings, each with its "Ground floor"): a name
  // must say which storey it means. storeyLookupError says why it found none, naming `file`.
  const Storey* findStorey(const std::string& name_or_index) const;
  std::string storeyLookupError(const std::string& name_or_index) const;
  // The storey's name, or "name [#index]" where other storeys have the same name ("#index"
  // when it has none): what tables and messages call it, and what --storey takes back.
  std::string storeyLabel(std::size_t index) const;
};

}  // namespace bimloc::bim
