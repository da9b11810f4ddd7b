// PlanGrid's input, and the walls its labels imply. Rooms, outline and doors: plan_regions.cpp.
#include "sim/worldgen/plan_grid.hpp"

#include "sim/worldgen/plan_grid_detail.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace bimloc::worldgen {

void PlanGrid::addLine(std::map<Mm, Mm>& lines, Mm pos, Mm thickness) {
  if (pos % 5 != 0 || thickness % 10 != 0 || thickness <= 0) {
    throw std::logic_error("plan grid: line at " + std::to_string(pos) + " mm, " + std::to_string(thickness) +
                           " mm thick: positions must be multiples of 5 mm, thicknesses of 10 mm");
  }
  const auto [it, added] = lines.emplace(pos, thickness);
  if (!added && it->second != thickness) {
    throw LayoutConflict("plan grid: two lines at " + std::to_string(pos) + " mm, " + std::to_string(it->second) +
                         " and " + std::to_string(thickness) + " mm thick");
  }
}

int PlanGrid::addRoom(const std::string& name, const std::string& long_name) {
  rooms_.push_back({name, long_name});
  return static_cast<int>(rooms_.size()) - 1;
}

void PlanGrid::paint(Mm x0, Mm y0, Mm x1, Mm y1, int label) {
  if (!xs_.count(x0) || !xs_.count(x1) || !ys_.count(y0) || !ys_.count(y1) || x0 >= x1 || y0 >= y1) {
    throw std::logic_error("plan grid: paint [" + std::to_string(x0) + ", " + std::to_string(x1) + "] x [" +
                           std::to_string(y0) + ", " + std::to_string(y1) + "] is not between declared lines");
  }
  paints_.push_back({x0, y0, x1, y1, label});
}

int PlanGrid::door(bool along_x, Mm line_pos, Mm centre, Mm width_mm, Mm height_mm) {
  doors_.push_back({along_x, line_pos, centre, width_mm, height_mm});
  return static_cast<int>(doors_.size()) - 1;
}

void PlanGrid::freeWall(bool along_x, Mm at, Mm from, Mm to, Mm thickness_mm) {
  free_walls_.push_back({along_x, at, std::min(from, to), std::max(from, to), thickness_mm});
}

namespace plan_detail {

int CellGrid::labelAtDoubled(Mm x2, Mm y2) const {
  const auto cell = [](const std::vector<Mm>& lines, Mm v2) {  // lines[i] < v / 2 <= lines[i + 1]
    const auto it = std::lower_bound(lines.begin(), lines.end(), v2, [](Mm line, Mm v) { return 2 * line < v; });
    return static_cast<int>(it - lines.begin()) - 1;
  };
  return at(cell(xs, x2), cell(ys, y2));
}

namespace {

// One piece of wall material: the edge between two cells along a line.
struct Segment {
  bool present = false;
  Mm demand = 0;  // thickness it asks for
  bool exterior = false;
  int run = -1;
};

struct Run {
  bool along_x;
  int line;       // index into the grid's ys (along x) or xs (along y)
  int first, last;  // nodes (indices of the perpendicular lines) it spans
  Mm thickness = 0;
  bool exterior = false;
};

}  // namespace

std::vector<BoxWall> wallsOf(const CellGrid& g, Mm exterior_mm) {
  const int nx = g.nx(), ny = g.ny();
  const int lx = nx + 1, ly = ny + 1;  // line counts
  // h[j][i]: along line y = ys[j] between xs[i] and xs[i+1]; v[i][j]: along x = xs[i].
  std::vector<Segment> h(static_cast<std::size_t>(ly * nx)), v(static_cast<std::size_t>(lx * ny));
  auto H = [&](int j, int i) -> Segment* { return i < 0 || i >= nx || j < 0 || j >= ly ? nullptr : &h[j * nx + i]; };
  auto V = [&](int i, int j) -> Segment* { return j < 0 || j >= ny || i < 0 || i >= lx ? nullptr : &v[i * ny + j]; };
  const auto set = [&](Segment& s, int a, int b, Mm interior) {
    s.present = a != b;
    s.exterior = a == PlanGrid::kOutside || b == PlanGrid::kOutside;
    s.demand = s.exterior ? std::max(exterior_mm, interior) : interior;
  };
  for (int j = 0; j < ly; ++j)
    for (int i = 0; i < nx; ++i) set(*H(j, i), g.at(i, j - 1), g.at(i, j), g.ty[j]);
  for (int i = 0; i < lx; ++i)
    for (int j = 0; j < ny; ++j) set(*V(i, j), g.at(i - 1, j), g.at(i, j), g.tx[i]);
  const auto on = [](const Segment* s) { return s && s->present; };

  // Runs: contiguous material along a line. Walls along x run through every junction; walls
  // along y stop at a crossing (a wall along x on both sides of the node).
  std::vector<Run> runs;
  for (int j = 0; j < ly; ++j)
    for (int i = 0; i < nx; ++i) {
      if (!on(H(j, i))) continue;
      if (!on(H(j, i - 1))) runs.push_back({true, j, i, i});
      Run& r = runs.back();
      r.last = i + 1;
      r.thickness = std::max(r.thickness, H(j, i)->demand);
      r.exterior = r.exterior || H(j, i)->exterior;
      H(j, i)->run = static_cast<int>(runs.size()) - 1;
    }
  for (int i = 0; i < lx; ++i)
    for (int j = 0; j < ny; ++j) {
      if (!on(V(i, j))) continue;
      const bool crossing = on(H(j, i - 1)) && on(H(j, i));
      if (!on(V(i, j - 1)) || crossing) runs.push_back({false, i, j, j});
      Run& r = runs.back();
      r.last = j + 1;
      r.thickness = std::max(r.thickness, V(i, j)->demand);
      r.exterior = r.exterior || V(i, j)->exterior;
      V(i, j)->run = static_cast<int>(runs.size()) - 1;
    }

  // How far a run's end reaches past its node: to the far face (+), the near face (-).
  const auto thick = [&](const Segment* a, const Segment* b) {
    return runs[(on(a) ? a : b)->run].thickness;
  };
  const auto reach = [&](const Run& r, int node, bool at_end) -> Mm {
    const int i = r.along_x ? node : r.line, j = r.along_x ? r.line : node;
    const Segment *w = H(j, i - 1), *e = H(j, i), *s = V(i, j - 1), *n = V(i, j);
    const bool across_a = r.along_x ? on(s) : on(w), across_b = r.along_x ? on(n) : on(e);
    const Mm t_across = r.along_x ? (across_a || across_b ? thick(s, n) : 0) : (across_a || across_b ? thick(w, e) : 0);
    if (across_a && across_b) return -t_across / 2;  // T or crossing: end on the through wall's face
    if (!across_a && !across_b) {
      throw std::logic_error("plan grid: a wall ends free at node (" + std::to_string(g.xs[i]) + ", " +
                             std::to_string(g.ys[j]) + ")");
    }
    // A corner: the quadrant opposite the two arms is the outer side of the corner.
    const int di = r.along_x ? (at_end ? 0 : -1) : (across_b ? -1 : 0);
    const int dj = r.along_x ? (across_b ? -1 : 0) : (at_end ? 0 : -1);
    const bool outer_is_outside = g.at(i + di, j + dj) == PlanGrid::kOutside;
    // Outside the building one wall is enough over the corner: the one along x.
    if (outer_is_outside && !r.along_x) return -t_across / 2;
    return t_across / 2;
  };

  std::vector<BoxWall> walls;
  int exterior_count = 0, interior_count = 0;
  for (const Run& r : runs) {
    const std::vector<Mm>& along = r.along_x ? g.xs : g.ys;
    BoxWall w;
    w.along_x = r.along_x;
    w.axis = r.along_x ? g.ys[r.line] : g.xs[r.line];
    w.from = along[r.first] - reach(r, r.first, false);
    w.to = along[r.last] + reach(r, r.last, true);
    w.thickness = r.thickness;
    w.exterior = r.exterior;
    char name[16];
    std::snprintf(name, sizeof name, "%s-%03d", r.exterior ? "EXT" : "INT",
                  r.exterior ? ++exterior_count : ++interior_count);
    w.name = name;
    if (w.to - w.from < std::max<Mm>(300, w.thickness)) {
      throw std::logic_error("plan grid: wall " + w.name + " is only " + std::to_string(w.to - w.from) + " mm long");
    }
    walls.push_back(w);
  }
  return walls;
}

}  // namespace plan_detail
}  // namespace bimloc::worldgen
