// The interpretation steps that turn a RawModel into the building model, each a pure
// function of plain data (tested without any IFC file).
#pragma once

#include "raw_model.hpp"

#include <bimloc/bim/building.hpp>
#include <bimloc/bim/ifc_reader.hpp>

#include <optional>
#include <string>

namespace bimloc::bim::detail {

// Each raw storey's floor height in the geometry's frame, in raw.storeys' order, and where it
// came from ("placement", "Elevation", or "none": 0 m, named in `warnings`); storey_levels.cpp.
struct StoreyLevel {
  double elevation_m = 0.0;
  std::string source;
};
std::vector<StoreyLevel> storeyLevels(const RawModel& raw, std::vector<std::string>& warnings);

// No building is this long, in metres (the longest are about a kilometre): a wall or room this
// far from the middle of the plan's walls, or this high or deep, is damage. One room vertex
// written 1e30 m out overflowed every grid sized by a storey's extent (the simulator's room
// lookup, the filter's room index: a segfault). Such an element is skipped and named, as one
// without geometry, and building.json refuses it. Measured from the walls' middle, not the
// origin: a plan whose vertices carry surveyed coordinates is still read.
constexpr double kFarthestElementM = 1e5;
// The middle of the plan: the median x and y of the points (the walls' ends), robust to the few
// a damaged file throws far out; zero when there is none.
Eigen::Vector2d planMiddle(std::vector<Eigen::Vector2d> points);
// Why the wall (its ends, base to top) or the room (its footprint, floor to ceiling) is out of
// the plan ("" when no point of it is that far from `middle`): the one rule of readIfc and of
// buildingFromJson.
std::string farFromPlan(const Wall& wall, const Eigen::Vector2d& middle);
std::string farFromPlan(const Room& room, const Eigen::Vector2d& middle);

// A wall as a straight box: axis, thickness, height and its two faces (paper Eq. 1 and 2).
// Returns nothing and says why in `problem` when the product has no usable geometry.
std::optional<Wall> wallFromGeometry(const RawProduct& product, std::string& problem);

// The openings of a wall face (windows, doors, recesses) from the wall's body mesh, openings
// cut: the rectangles of at least 0.3 m x 0.3 m on the face, between z0 and z0 + height_m,
// where no triangle of the body lies on it (face_openings.cpp). None when the body has no
// triangle on the face at all.
std::vector<FaceOpening> faceOpenings(const WallFace& face, double z0, double height_m, const TriangleMesh& body);

// A curtain wall (IfcCurtainWall) as one body: its own, if any, and its parts' (IfcRelAggregates:
// plates, members), with the wall box fitted to it (curtain_walls.cpp).
struct CurtainWall {
  RawProduct body;  // the curtain wall's ids and name, the mesh of all its parts
  int parts = 0;
  Wall wall;  // the box of the assembly (its faces the outermost surfaces)
  // How far each face of `wall` lies in front of the assembly's main surface on that side
  // (visibleSurfaceDepths); moveFacesToVisibleSurfaces applies it once the rooms are linked.
  std::array<double, 2> visible_depth_m{0.0, 0.0};
};

bool isCurtainWall(const RawProduct& product);

// The straight curtain walls of the model as walls; the others are named in `warnings`.
std::vector<CurtainWall> curtainWallsOf(const RawModel& raw, std::vector<std::string>& warnings);

// For each face of `wall`, the depth behind it (>= 0, metres) of the surface with the most
// area among the mesh's surfaces facing the same way: what a lidar sees of that side.
std::array<double, 2> visibleSurfaceDepths(const TriangleMesh& mesh, const Wall& wall);

// Moves each face back by its depth (along -normal), keeping the wall's box and axis.
void moveFacesToVisibleSurfaces(Wall& wall, const std::array<double, 2>& depth_m);

// A room's footprint, area and centre from its space's body.
std::optional<Room> roomFromGeometry(const RawProduct& space, std::string& problem);

// Does `face` lie on the footprint edge a→b of a counter-clockwise room polygon, looking in?
bool faceBoundsEdge(const WallFace& face, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                    const ExtractOptions& options);

// Does the footprint edge a→b run inside the body of `wall` (between its faces, or on one),
// with face `f` looking into the room? Rooms drawn to a wall's centre line, or to the outer
// line of a curtain wall's assembly, are bounded by it as much as rooms drawn to its face.
bool edgeInWallBody(const Wall& wall, int f, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                    const ExtractOptions& options);

// Fills Room::walls for every room of the storey: IfcRelSpaceBoundary where the file has
// it for that room, otherwise the wall faces lying on the room's footprint.
void linkRoomsToWalls(Storey& storey, const std::vector<SpaceBoundary>& boundaries,
                      const ExtractOptions& options);

// Room::walls from geometry alone: the wall faces lying on the room's footprint, looking in.
void linkRoomByGeometry(Room& room, const std::vector<Wall>& walls, const ExtractOptions& options);

// Triangles of a vertical prism (for bodies read from their extrusion).
TriangleMesh prismMesh(const Extrusion& extrusion);

void appendMesh(TriangleMesh& target, const TriangleMesh& source);

// The same surface, cut into triangles from the outline of each of its planes (triangles of
// one plane sharing corners), in an order of their coordinates: the bytes depend on the
// surface alone, not on how IFC++'s CSG happened to split it (see canonical_mesh.cpp).
// Degenerate triangles are dropped; a plane whose outline is not a set of polygons with
// holes keeps its triangles.
void canonicalSurface(TriangleMesh& mesh);

}  // namespace bimloc::bim::detail
