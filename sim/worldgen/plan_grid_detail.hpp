// PlanGrid's internals, shared by plan_grid.cpp (walls from the labelled grid) and
// plan_regions.cpp (rooms, outline and doors from the walls). Integer millimetres throughout.
#pragma once

#include "sim/worldgen/plan_grid.hpp"

#include <string>
#include <vector>

namespace bimloc::worldgen::plan_detail {

// A straight box wall: along x it covers [from, to] × [axis - t/2, axis + t/2], along y the
// same with x and y swapped.
struct BoxWall {
  bool along_x = true;
  Mm axis = 0, from = 0, to = 0, thickness = 0;
  bool exterior = false;
  std::string name;
  Mm faceLow() const { return axis - thickness / 2; }
  Mm faceHigh() const { return axis + thickness / 2; }
};

// The labelled cells, as the lines cut the plane.
struct CellGrid {
  std::vector<Mm> xs, ys;  // line positions, ascending
  std::vector<Mm> tx, ty;  // their interior thicknesses
  std::vector<int> label;  // (xs.size() - 1) × (ys.size() - 1), row by row
  int nx() const { return static_cast<int>(xs.size()) - 1; }
  int ny() const { return static_cast<int>(ys.size()) - 1; }
  int at(int i, int j) const {
    return i < 0 || j < 0 || i >= nx() || j >= ny() ? PlanGrid::kOutside : label[i + nx() * j];
  }
  // The cell containing the point whose doubled coordinates are (x2, y2), or kOutside.
  int labelAtDoubled(Mm x2, Mm y2) const;
};

// The walls the grid's labels imply (see plan_grid.hpp), named EXT-nnn and INT-nnn.
std::vector<BoxWall> wallsOf(const CellGrid& grid, Mm exterior_mm);

// The plane cut at every wall face and line: each cell is one room, wall or outside.
struct Raster {
  static constexpr int kWall = -2;
  std::vector<Mm> cx, cy;
  std::vector<int> state;
  int nx() const { return static_cast<int>(cx.size()) - 1; }
  int ny() const { return static_cast<int>(cy.size()) - 1; }
  int at(int a, int b) const {
    return a < 0 || b < 0 || a >= nx() || b >= ny() ? PlanGrid::kOutside : state[a + nx() * b];
  }
  int indexX(Mm x) const;  // index of an exact coordinate of cx
  int indexY(Mm y) const;
};
Raster rasterize(const CellGrid& grid, const std::vector<BoxWall>& walls);

// A traced boundary: corners in mm, counter-clockwise around the region, and for each edge
// (from corner k to k + 1) the wall whose face it lies on (-1 for the outline).
struct Boundary {
  std::vector<std::pair<Mm, Mm>> corners;
  std::vector<int> walls;
};
constexpr int kBuilding = -3;  // traceRegion's label for every cell that is not outside
// The boundary of the cells of `label` (a room, or kBuilding); throws std::logic_error naming
// `what` when that region is not one simple polygon, when an edge of a room lies on no wall
// face, or when an edge is shorter than 0.3 m.
Boundary traceRegion(const Raster& raster, const std::vector<BoxWall>& walls, int label, const std::string& what);

}  // namespace bimloc::worldgen::plan_detail
