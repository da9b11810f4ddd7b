// PlanGrid::build: the walls (plan_grid.cpp), then the rooms' footprints and the outline traced
// on the plane cut at every wall face, then the doors and the free-standing walls.
#include "sim/worldgen/plan_grid.hpp"

#include "sim/worldgen/plan_grid_detail.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <stdexcept>

namespace bimloc::worldgen {
namespace plan_detail {
namespace {

int indexOf(const std::vector<Mm>& coords, Mm v) {
  const auto it = std::lower_bound(coords.begin(), coords.end(), v);
  if (it == coords.end() || *it != v) throw std::logic_error("plan grid: " + std::to_string(v) + " mm is not a cut");
  return static_cast<int>(it - coords.begin());
}

void sortUnique(std::vector<Mm>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

double metres(Mm mm) { return static_cast<double>(mm) / 1000.0; }

}  // namespace

int Raster::indexX(Mm x) const { return indexOf(cx, x); }
int Raster::indexY(Mm y) const { return indexOf(cy, y); }

Raster rasterize(const CellGrid& grid, const std::vector<BoxWall>& walls) {
  Raster r;
  r.cx = grid.xs, r.cy = grid.ys;
  for (const BoxWall& w : walls) {
    std::vector<Mm>& along = w.along_x ? r.cx : r.cy;
    std::vector<Mm>& across = w.along_x ? r.cy : r.cx;
    along.push_back(w.from), along.push_back(w.to);
    across.push_back(w.faceLow()), across.push_back(w.faceHigh());
  }
  sortUnique(r.cx), sortUnique(r.cy);
  r.state.resize(static_cast<std::size_t>(r.nx() * r.ny()));
  for (int b = 0; b < r.ny(); ++b)
    for (int a = 0; a < r.nx(); ++a) r.state[a + r.nx() * b] = grid.labelAtDoubled(r.cx[a] + r.cx[a + 1], r.cy[b] + r.cy[b + 1]);
  for (const BoxWall& w : walls) {
    const int a0 = r.indexX(w.along_x ? w.from : w.faceLow()), a1 = r.indexX(w.along_x ? w.to : w.faceHigh());
    const int b0 = r.indexY(w.along_x ? w.faceLow() : w.from), b1 = r.indexY(w.along_x ? w.faceHigh() : w.to);
    for (int b = b0; b < b1; ++b)
      for (int a = a0; a < a1; ++a) r.state[a + r.nx() * b] = Raster::kWall;
  }
  return r;
}

Boundary traceRegion(const Raster& r, const std::vector<BoxWall>& walls, int label, const std::string& what) {
  const auto inside = [&](int s) { return label == kBuilding ? s != PlanGrid::kOutside : s == label; };
  // Faces of the walls along x (y of the face -> walls) and along y, by the side a room sees.
  // Indexed by the direction of the room's edge: +x (the wall below it), +y (east), -x, -y.
  std::multimap<Mm, int> faces[4];
  for (int k = 0; k < static_cast<int>(walls.size()); ++k) {
    const BoxWall& w = walls[k];
    faces[w.along_x ? 0 : 3].emplace(w.faceHigh(), k);
    faces[w.along_x ? 2 : 1].emplace(w.faceLow(), k);
  }
  // Unit edges with the region on their left; dir 0 +x, 1 +y, 2 -x, 3 -y.
  struct Edge {
    int from, to, dir, wall;
  };
  const int vx = r.nx() + 1;
  std::vector<Edge> edges;
  std::map<int, int> starting;  // vertex -> edge
  for (int b = 0; b < r.ny(); ++b)
    for (int a = 0; a < r.nx(); ++a) {
      if (!inside(r.at(a, b))) continue;
      const int v00 = a + vx * b, v10 = v00 + 1, v01 = v00 + vx, v11 = v01 + 1;
      const int na[4] = {a, a + 1, a, a - 1}, nb[4] = {b - 1, b, b + 1, b};
      const int from[4] = {v00, v10, v11, v01}, to[4] = {v10, v11, v01, v00};
      for (int d = 0; d < 4; ++d) {
        const int other = r.at(na[d], nb[d]);
        if (inside(other)) continue;
        int wall = -1;
        if (label != kBuilding) {
          if (other != Raster::kWall) {
            throw std::logic_error("plan grid: " + what + " touches " +
                                   (other == PlanGrid::kOutside ? std::string("the outside") : "room " + std::to_string(other)) +
                                   " without a wall at (" + std::to_string(r.cx[a]) + ", " + std::to_string(r.cy[b]) + ") mm");
          }
          const Mm fixed = d == 0 ? r.cy[b] : d == 1 ? r.cx[a + 1] : d == 2 ? r.cy[b + 1] : r.cx[a];
          const Mm lo = d % 2 == 0 ? r.cx[a] : r.cy[b], hi = d % 2 == 0 ? r.cx[a + 1] : r.cy[b + 1];
          const auto range = faces[d].equal_range(fixed);
          for (auto it = range.first; it != range.second; ++it) {
            const BoxWall& w = walls[it->second];
            if (w.from > lo || w.to < hi) continue;
            if (wall >= 0) throw std::logic_error("plan grid: " + what + " lies on two walls: " + walls[wall].name + ", " + w.name);
            wall = it->second;
          }
          if (wall < 0) {
            throw std::logic_error("plan grid: an edge of " + what + " at " + std::string(d % 2 == 0 ? "y" : "x") + " = " +
                                   std::to_string(fixed) + " mm, from " + std::to_string(lo) + " to " + std::to_string(hi) +
                                   " mm, lies on no wall face");
          }
        }
        if (!starting.emplace(from[d], static_cast<int>(edges.size())).second) {
          throw std::logic_error("plan grid: " + what + " pinches at a corner");
        }
        edges.push_back({from[d], to[d], d, wall});
      }
    }
  if (edges.empty()) throw std::logic_error("plan grid: " + what + " is empty");
  // Walk the loop from the first edge; it must use every edge (one polygon, no hole).
  Boundary out;
  std::size_t walked = 0;
  int e = 0, previous_dir = -1, previous_wall = -2;
  do {
    const Edge& edge = edges[e];
    if (edge.dir != previous_dir || edge.wall != previous_wall) {
      out.corners.emplace_back(r.cx[edge.from % vx], r.cy[edge.from / vx]);
      out.walls.push_back(edge.wall);
    }
    previous_dir = edge.dir, previous_wall = edge.wall;
    ++walked;
    const auto next = starting.find(edge.to);
    if (next == starting.end()) throw std::logic_error("plan grid: " + what + " has an open boundary");
    e = next->second;
  } while (e != 0 && walked <= edges.size());
  if (walked != edges.size()) throw std::logic_error("plan grid: " + what + " is not one simple polygon");
  std::vector<std::pair<Mm, Mm>>& c = out.corners;
  const auto direction = [&](std::size_t k) {
    const auto &p = c[k], &q = c[(k + 1) % c.size()];
    return std::make_pair((q.first > p.first) - (q.first < p.first), (q.second > p.second) - (q.second < p.second));
  };
  // Drop a corner where the same wall (or, for the outline, the same direction) continues: the
  // walk may have started in the middle of an edge.
  for (std::size_t k = 0; k < c.size() && c.size() > 3;) {
    const std::size_t prev = (k + c.size() - 1) % c.size();
    if (direction(prev) == direction(k) && out.walls[prev] == out.walls[k]) {
      c.erase(c.begin() + static_cast<long>(k));
      out.walls.erase(out.walls.begin() + static_cast<long>(k));
      k = 0;
    } else {
      ++k;
    }
  }
  for (std::size_t k = 0; k < c.size(); ++k) {
    const auto &p = c[k], &q = c[(k + 1) % c.size()];
    if (std::abs(q.first - p.first) + std::abs(q.second - p.second) < 300) {
      throw LayoutConflict("plan grid: " + what + " has an edge shorter than 0.3 m at (" + std::to_string(p.first) +
                             ", " + std::to_string(p.second) + ") mm");
    }
  }
  return out;
}

}  // namespace plan_detail

namespace {

using namespace plan_detail;

// Cells of `coords` overlapping the open interval (lo, hi): [first, second).
std::pair<int, int> cellsOver(const std::vector<Mm>& coords, Mm lo, Mm hi) {
  const int first = static_cast<int>(std::upper_bound(coords.begin(), coords.end(), lo) - coords.begin()) - 1;
  const int last = static_cast<int>(std::lower_bound(coords.begin(), coords.end(), hi) - coords.begin());
  return {first, last};
}

// The one state of the raster cells overlapping the box, or kWall when they differ.
int stateOver(const Raster& r, Mm x0, Mm y0, Mm x1, Mm y1) {
  const auto [a0, a1] = cellsOver(r.cx, x0, x1);
  const auto [b0, b1] = cellsOver(r.cy, y0, y1);
  int state = r.at(a0, b0);
  for (int b = b0; b < b1; ++b)
    for (int a = a0; a < a1; ++a)
      if (r.at(a, b) != state) return Raster::kWall;
  return state;
}

}  // namespace

PlanGrid::Result PlanGrid::build(const std::string& storey_name, double height_m, double slab_m,
                                 double wall_height_m) const {
  CellGrid grid;
  for (const auto& [pos, t] : xs_) grid.xs.push_back(pos), grid.tx.push_back(t);
  for (const auto& [pos, t] : ys_) grid.ys.push_back(pos), grid.ty.push_back(t);
  if (grid.nx() < 1 || grid.ny() < 1) throw std::logic_error("plan grid: no cells");
  grid.label.assign(static_cast<std::size_t>(grid.nx() * grid.ny()), kOutside);
  for (const Paint& p : paints_) {
    const int i0 = indexOf(grid.xs, p.x0), i1 = indexOf(grid.xs, p.x1);
    const int j0 = indexOf(grid.ys, p.y0), j1 = indexOf(grid.ys, p.y1);
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) grid.label[i + grid.nx() * j] = p.label;
  }
  const std::vector<BoxWall> walls = wallsOf(grid, exterior_mm_);
  const Raster raster = rasterize(grid, walls);

  Result result;
  StoreySpec& storey = result.storey;
  storey.name = storey_name;
  storey.height_m = height_m;
  storey.slab_thickness_m = slab_m;
  for (const BoxWall& w : walls) {
    const Eigen::Vector2d a(metres(w.from), metres(w.axis)), b(metres(w.to), metres(w.axis));
    storey.walls.push_back({w.name, w.along_x ? a : a.reverse().eval(), w.along_x ? b : b.reverse().eval(),
                            metres(w.thickness), wall_height_m, w.exterior});
  }
  for (int k = 0; k < static_cast<int>(rooms_.size()); ++k) {
    const Boundary boundary = traceRegion(raster, walls, k, "room " + rooms_[k].name);
    RoomSpec room{rooms_[k].name, rooms_[k].long_name, {}, {}, {}};
    for (std::size_t e = 0; e < boundary.corners.size(); ++e) {
      room.footprint.emplace_back(metres(boundary.corners[e].first), metres(boundary.corners[e].second));
      if (std::find(room.walls.begin(), room.walls.end(), boundary.walls[e]) == room.walls.end()) {
        room.walls.push_back(boundary.walls[e]);
      }
    }
    storey.rooms.push_back(std::move(room));
  }
  for (const auto& [x, y] : traceRegion(raster, walls, kBuilding, "the building").corners) {
    storey.outline.emplace_back(metres(x), metres(y));
  }

  result.room_doors.assign(rooms_.size(), 0);
  std::vector<std::vector<std::pair<Mm, Mm>>> openings(walls.size());
  for (const DoorRequest& d : doors_) {
    const std::string at = "plan grid: door on line " + std::to_string(d.line) + " at " + std::to_string(d.centre) + " mm";
    const Mm lo = d.centre - d.width / 2, hi = d.centre + d.width / 2;
    int wall = -1;
    for (int k = 0; k < static_cast<int>(walls.size()); ++k)
      if (walls[k].along_x == d.along_x && walls[k].axis == d.line && walls[k].from <= lo && walls[k].to >= hi) wall = k;
    if (wall < 0 || d.centre % 5 != 0 || d.width % 10 != 0) throw std::logic_error(at + ": no wall holds it");
    const BoxWall& w = walls[wall];
    // Each side of the opening, 5 cm past its edges, must be one room (or the outside).
    const Mm m = 50, f0 = w.faceLow(), f1 = w.faceHigh();
    const int side0 = d.along_x ? stateOver(raster, lo - m, f0 - 1, hi + m, f0) : stateOver(raster, f0 - 1, lo - m, f0, hi + m);
    const int side1 = d.along_x ? stateOver(raster, lo - m, f1, hi + m, f1 + 1) : stateOver(raster, f1, lo - m, f1 + 1, hi + m);
    if (side0 == Raster::kWall || side1 == Raster::kWall || side0 == side1) {
      throw std::logic_error(at + ": does not open from one room into another");
    }
    for (const auto& [o0, o1] : openings[wall])
      if (lo < o1 + 300 && hi > o0 - 300) throw std::logic_error(at + ": too close to another door in " + w.name);
    openings[wall].emplace_back(lo, hi);
    storey.doors.push_back({wall, metres(d.centre - w.from), metres(d.width), metres(d.height)});
    result.door_rooms.emplace_back(side0, side1);
    for (int side : {side0, side1})
      if (side >= 0) ++result.room_doors[side];
  }

  // Free-standing walls: inside one room, at least 0.9 m from every other wall.
  std::vector<std::array<Mm, 4>> placed;
  int free_count = 0;
  for (const FreeWall& f : free_walls_) {
    const Mm t = f.thickness / 2, c = 900;
    const std::array<Mm, 4> box = f.along_x ? std::array<Mm, 4>{f.from, f.at - t, f.to, f.at + t}
                                            : std::array<Mm, 4>{f.at - t, f.from, f.at + t, f.to};
    bool clear = stateOver(raster, box[0] - c, box[1] - c, box[2] + c, box[3] + c) >= 0;
    for (const auto& p : placed)
      clear = clear && (box[0] - c >= p[2] || box[2] + c <= p[0] || box[1] - c >= p[3] || box[3] + c <= p[1]);
    if (!clear) throw std::logic_error("plan grid: free wall at " + std::to_string(f.at) + " mm does not stand clear in a room");
    placed.push_back(box);
    char name[16];
    std::snprintf(name, sizeof name, "FREE-%02d", ++free_count);
    const Eigen::Vector2d a(metres(f.from), metres(f.at)), b(metres(f.to), metres(f.at));
    storey.walls.push_back({name, f.along_x ? a : a.reverse().eval(), f.along_x ? b : b.reverse().eval(),
                            metres(f.thickness), wall_height_m, false});
  }
  return result;
}

}  // namespace bimloc::worldgen
