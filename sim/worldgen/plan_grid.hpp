// A floor plan drawn the way the random worlds are drawn: wall axis lines on a rectilinear
// grid, every grid cell labelled with the room it belongs to (or outside), doors on the lines.
// build() derives everything a StoreySpec needs, exactly, in integer millimetres:
//  - a wall wherever two cells of different labels meet (exterior thickness when one side is
//    outside), merged along a line into straight box walls; at junctions the through wall
//    continues and the other ends on its face (T), at corners both run over the corner square
//    (L), except at the building's outer corners where one runs over as in worlds.cpp;
//  - each room's clear footprint: its cells minus the wall boxes, traced counter-clockwise, with
//    a vertex wherever the wall under the edge changes, so every edge lies on one wall face;
//  - the outline (outer faces of the exterior walls) and the doors' offsets along their walls.
// Anything inconsistent (a room touching another room without a wall, a hole, a door that
// does not fit between its jambs) throws std::logic_error: a bug in whoever drew the plan.
#pragma once

#include "sim/worldgen/world_spec.hpp"

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace bimloc::worldgen {

using Mm = std::int64_t;  // millimetres; positions are multiples of 5, thicknesses of 10

// A plan that does not fit together although each part is valid: two lines of different
// thickness at one place, or a room edge shorter than 0.3 m where two faces almost meet. A
// random generator draws again; anything else PlanGrid throws is a std::logic_error (a bug).
struct LayoutConflict : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class PlanGrid {
 public:
  static constexpr int kOutside = -1;

  explicit PlanGrid(Mm exterior_mm) : exterior_mm_(exterior_mm) {}

  // A wall axis line x = pos (walls along y) or y = pos (walls along x); `thickness_mm` is the
  // thickness of its interior walls. Declaring a line twice with another thickness is a
  // LayoutConflict.
  void lineX(Mm pos, Mm thickness_mm) { addLine(xs_, pos, thickness_mm); }
  void lineY(Mm pos, Mm thickness_mm) { addLine(ys_, pos, thickness_mm); }

  int addRoom(const std::string& name, const std::string& long_name);
  std::string& longName(int room) { return rooms_.at(room).long_name; }
  int roomCount() const { return static_cast<int>(rooms_.size()); }

  // Labels the cells of [x0, x1] × [y0, y1] (axis coordinates, lines declared); later paints
  // win over earlier ones.
  void paint(Mm x0, Mm y0, Mm x1, Mm y1, int label);

  // A door in the wall on line y = line_pos (along_x) or x = line_pos, centred at `centre` along
  // the line. Returns its index.
  int door(bool along_x, Mm line_pos, Mm centre, Mm width_mm, Mm height_mm);

  // A free-standing wall (no room's boundary) along x or y from `from` to `to` at `at`.
  void freeWall(bool along_x, Mm at, Mm from, Mm to, Mm thickness_mm);

  struct Result {
    StoreySpec storey;
    std::vector<std::pair<int, int>> door_rooms;  // per door of the storey: the two labels
    std::vector<int> room_doors;                  // doors per room
  };
  // Walls are `wall_height_m` high; the storey gets name and heights from the arguments.
  Result build(const std::string& storey_name, double height_m, double slab_m, double wall_height_m) const;

 private:
  struct DoorRequest {
    bool along_x;
    Mm line, centre, width, height;
  };
  struct FreeWall {
    bool along_x;
    Mm at, from, to, thickness;
  };
  struct Paint {
    Mm x0, y0, x1, y1;
    int label;
  };
  struct RoomInfo {
    std::string name, long_name;
  };
  static void addLine(std::map<Mm, Mm>& lines, Mm pos, Mm thickness);

  Mm exterior_mm_;
  std::map<Mm, Mm> xs_, ys_;
  std::vector<Paint> paints_;
  std::vector<RoomInfo> rooms_;
  std::vector<DoorRequest> doors_;
  std::vector<FreeWall> free_walls_;
};

}  // namespace bimloc::worldgen
