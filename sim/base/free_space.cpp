#include "sim/base/free_space.hpp"

#include "sim/base/room_lookup.hpp"
#include "sim/world/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <queue>
#include <stdexcept>
#include <vector>

namespace bimloc::sim {
namespace {

// E, NE, N, NW, W, SW, S, SE: direction d + 4 is the reverse of d.
constexpr int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr int kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
// Spot test: a Bullet sweep that starts inside the mesh may report nothing when it moves away
// from the surface, so a spot is tested by tiny sweeps in the four directions: at least one of
// them moves into whatever the body overlaps.
constexpr double kNudge_m = 1e-3;
// Grid margin around the rooms and walls: room to walk around the outside of the building.
constexpr double kGridPad_m = 1.0;
// Cells are numbered by int. The grid's cells are stored in chunks made where a search goes
// (chunked_cells.hpp), so a large storey costs what its paths touch: a billion cells is a
// storey 1.58 km square. Beyond it, the plan is damaged (a wall a million kilometres long).
constexpr std::size_t kMaxCells = 1'000'000'000;

// The floor around a spot (bodyCentreZ): the surfaces under a 7 x 7 grid 0.5 m apart (3 x 3 m,
// more than a table, a bed or a sofa covers of it), and how far above their median a surface is
// still the floor: a finish varies by a floating screed's thickness, 45 mm and more, plus a rug
// or a threshold (the localizer's StoreyFollowConfig::floor_finish_m, 0.12 m).
constexpr int kFloorAroundSteps = 3;
constexpr double kFloorAroundStepM = 0.5;
constexpr double kFloorFinishM = 0.12;

Eigen::Vector3d at(const Eigen::Vector2d& p, double z) { return {p.x(), p.y(), z}; }

}  // namespace

double bodyCentreZ(const World& world, std::size_t storey, const Eigen::Vector2d& p, double body_height_m) {
  const double elevation = world.building().storeys.at(storey).elevation_m;
  // Down from body height above the storey floor, to a little below it.
  const auto floorAt = [&](const Eigen::Vector2d& q, double* z) {
    return world.floorBelow(storey, at(q, elevation + body_height_m), body_height_m + 1.0, z);
  };
  double floor = elevation;
  if (!floorAt(p, &floor)) floor = elevation;
  // The first surface under p may be furniture: a coffee table or a sofa's seat below body
  // height. A base does not stand on it, and the floor the walk and its free space are planned
  // from is the floor (storeys are flat). Taken at a table top 0.38 m up (the Duplex's A102,
  // seed 1), the body was planned 0.37 m too high, over low furniture, and the odometry, which
  // starts on the floor the base stands on, read 0.37 m too high for the whole run
  // (docs/results/2026-11-27-h28duplex.md). The floor is what most of the ground around p is:
  // where p's surface stands above the median of the surfaces within kFloorAroundM by more than
  // a floor finish varies, the median is the floor.
  std::vector<double> around;
  for (int i = -kFloorAroundSteps; i <= kFloorAroundSteps; ++i)
    for (int j = -kFloorAroundSteps; j <= kFloorAroundSteps; ++j) {
      double z = 0.0;
      if (floorAt(p + kFloorAroundStepM * Eigen::Vector2d(i, j), &z)) around.push_back(z);
    }
  if (!around.empty()) {
    const auto middle = around.begin() + static_cast<std::ptrdiff_t>(around.size() / 2);
    std::nth_element(around.begin(), middle, around.end());
    if (floor > *middle + kFloorFinishM) floor = *middle;
  }
  return floor + body_height_m;
}

FreeSpace::FreeSpace(const World& world, std::size_t storey, double radius_m, double body_z_m)
    : world_(world), storey_(storey), rooms_(world.building().storeys.at(storey)), radius_(radius_m), body_z_(body_z_m) {}

bool FreeSpace::segmentClear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double margin_m,
                             Eigen::Vector3d* contact) const {
  if ((b - a).norm() < 1e-9) return spotFree(a, margin_m, contact);
  ++sweeps_;
  return world_.sweepClear(storey_, at(a, body_z_), at(b, body_z_), radius_ + margin_m, contact);
}

bool FreeSpace::spotFree(const Eigen::Vector2d& p, double margin_m, Eigen::Vector3d* contact) const {
  // The overlap test first: a sweep that starts inside a bed or a table does not see it.
  ++sweeps_;
  if (!world_.sphereClear(storey_, at(p, body_z_), radius_ + margin_m, contact)) return false;
  for (const Eigen::Vector2d& step : {Eigen::Vector2d(kNudge_m, 0.0), Eigen::Vector2d(-kNudge_m, 0.0),
                                      Eigen::Vector2d(0.0, kNudge_m), Eigen::Vector2d(0.0, -kNudge_m)}) {
    ++sweeps_;
    if (!world_.sweepClear(storey_, at(p - step, body_z_), at(p + step, body_z_), radius_ + margin_m, contact))
      return false;
  }
  return true;
}

std::optional<Eigen::Vector2d> FreeSpace::freeSpotNear(const Eigen::Vector2d& p, const bim::Polygon2* area,
                                                       double max_distance_m) const {
  const auto inside = [&](const Eigen::Vector2d& q) { return !area || bim::pointInPolygon(*area, q); };
  if (inside(p) && spotFree(p, kMargin_m)) return p;
  const int reach = static_cast<int>(std::ceil(max_distance_m / kCell_m));
  const long cx = std::lround(p.x() / kCell_m), cy = std::lround(p.y() / kCell_m);
  std::vector<std::pair<double, Eigen::Vector2d>> candidates;
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx) {
      const Eigen::Vector2d q((cx + dx) * kCell_m, (cy + dy) * kCell_m);
      const double d = (q - p).norm();
      if (d <= max_distance_m && inside(q)) candidates.emplace_back(d, q);
    }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const auto& l, const auto& r) { return l.first < r.first; });
  for (const auto& [d, q] : candidates)
    if (spotFree(q, kMargin_m)) return q;
  return std::nullopt;
}

void FreeSpace::makeGrid(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  Eigen::Vector2d lo = a.cwiseMin(b), hi = a.cwiseMax(b);
  const bim::Storey& storey = world_.building().storeys.at(storey_);
  for (const auto& room : storey.rooms)
    for (const auto& q : room.footprint) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  for (const auto& wall : storey.walls)
    for (const auto& face : wall.faces)
      for (const auto& q : {face.start, face.end}) lo = lo.cwiseMin(q.head<2>()), hi = hi.cwiseMax(q.head<2>());
  lo.array() -= kGridPad_m, hi.array() += kGridPad_m;
  // Cell centres on multiples of the cell size, so grids of one storey always coincide.
  grid_.origin = (lo / kCell_m).array().floor() * kCell_m;
  // Counted in double before any cast: a plan with a wall a million kilometres long (damage)
  // overflowed the int, and the message read 18446743431611941163 cells.
  const double nx = std::ceil((hi.x() - grid_.origin.x()) / kCell_m) + 1, ny = std::ceil((hi.y() - grid_.origin.y()) / kCell_m) + 1;
  if (!(nx * ny <= static_cast<double>(kMaxCells))) {
    char size[96];
    std::snprintf(size, sizeof size, "%.6g m x %.6g m", hi.x() - lo.x(), hi.y() - lo.y());
    throw std::runtime_error(world_.building().file + ": storey '" + storey.name + "' spans " + size + " (its rooms and walls): too large for the path grid (at most " +
                             std::to_string(kMaxCells) + " cells of " + std::to_string(kCell_m).substr(0, 4) + " m)");
  }
  grid_.nx = static_cast<int>(nx), grid_.ny = static_cast<int>(ny);
  const std::size_t cells = static_cast<std::size_t>(grid_.nx) * static_cast<std::size_t>(grid_.ny);
  grid_.edges = ChunkedCells<std::uint8_t>(cells, 0);
}

Eigen::Vector2d FreeSpace::centre(int cell) const {
  return grid_.origin + kCell_m * Eigen::Vector2d(cell % grid_.nx, cell / grid_.nx);
}

int FreeSpace::cellNear(const Eigen::Vector2d& p) const {
  const long ix = std::lround((p.x() - grid_.origin.x()) / kCell_m);
  const long iy = std::lround((p.y() - grid_.origin.y()) / kCell_m);
  if (ix < 0 || iy < 0 || ix >= grid_.nx || iy >= grid_.ny) return -1;
  return static_cast<int>(iy * grid_.nx + ix);
}

bool FreeSpace::edgeClear(int cell, int direction) {
  const int neighbour = cell + kDy[direction] * grid_.nx + kDx[direction];
  // Each edge is stored once, at the cell it leaves eastwards or northwards.
  const int owner = direction < 4 ? cell : neighbour;
  const int shift = 2 * (direction % 4);
  std::uint8_t& bits = grid_.edges.at(static_cast<std::size_t>(owner));
  const int state = (bits >> shift) & 3;
  if (state != 0) return state == 1;
  const bool clear = passable(centre(cell), centre(neighbour), kMargin_m);
  bits = static_cast<std::uint8_t>(bits | ((clear ? 1 : 2) << shift));
  return clear;
}

std::vector<int> FreeSpace::aStar(int from, int to, ChunkedCells<std::uint8_t>* reached) {
  const std::size_t n = grid_.edges.size();
  const float inf = std::numeric_limits<float>::infinity();
  ChunkedCells<float> g(n, inf);
  ChunkedCells<int> parent(n, -1);
  ChunkedCells<std::uint8_t> closed(n, 0);
  const int tx = to % grid_.nx, ty = to / grid_.nx;
  const auto h = [&](int c) {  // octile distance in cells (none without a goal: a flood)
    if (to < 0) return 0.0f;
    const int dx = std::abs(c % grid_.nx - tx), dy = std::abs(c / grid_.nx - ty);
    return static_cast<float>(std::max(dx, dy) + (M_SQRT2 - 1.0) * std::min(dx, dy));
  };
  using Item = std::pair<float, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  g.at(static_cast<std::size_t>(from)) = 0.0f;
  open.emplace(h(from), from);
  while (!open.empty()) {
    const int c = open.top().second;
    open.pop();
    if (closed[static_cast<std::size_t>(c)]) continue;
    closed.at(static_cast<std::size_t>(c)) = 1;
    if (c == to) break;
    const int cx = c % grid_.nx, cy = c / grid_.nx;
    for (int d = 0; d < 8; ++d) {
      const int x = cx + kDx[d], y = cy + kDy[d];
      if (x < 0 || y < 0 || x >= grid_.nx || y >= grid_.ny) continue;
      const int nb = y * grid_.nx + x;
      const float cost = g[static_cast<std::size_t>(c)] + static_cast<float>(d % 2 ? M_SQRT2 : 1.0);
      // Sweep only edges that would improve the neighbour: most are never swept at all.
      if (closed[static_cast<std::size_t>(nb)] || cost >= g[static_cast<std::size_t>(nb)] || !edgeClear(c, d)) continue;
      g.at(static_cast<std::size_t>(nb)) = cost;
      parent.at(static_cast<std::size_t>(nb)) = c;
      open.emplace(cost + h(nb), nb);
    }
  }
  if (to < 0 || !closed[static_cast<std::size_t>(to)]) {
    if (reached) *reached = std::move(closed);
    return {};
  }
  std::vector<int> cells{to};
  while (cells.back() != from) cells.push_back(parent[static_cast<std::size_t>(cells.back())]);
  std::reverse(cells.begin(), cells.end());
  return cells;
}

std::vector<Eigen::Vector2d> FreeSpace::pullTaut(const std::vector<Eigen::Vector2d>& points) const {
  // From each corner, go as far along the grid path as the straight line stays clear.
  std::vector<Eigen::Vector2d> corners{points.front()};
  std::size_t i = 0;
  const std::size_t last = points.size() - 1;
  while (i < last) {
    std::size_t k = i + 1;
    while (k < last && passable(points[i], points[k + 1], kMargin_m)) ++k;
    corners.push_back(points[k]);
    i = k;
  }
  return corners;
}

std::vector<Eigen::Vector2d> FreeSpace::straighten(std::vector<Eigen::Vector2d> c) const {
  // A taut path wraps around a rounded obstacle (a door jamb grown by the body) in several
  // short grid steps; each corner costs the base a stop and a turn. Drop corners the path can
  // do without, and replace two close corners by the crossing of the lines through them.
  bool changed = true;
  while (changed) {
    changed = false;
    for (std::size_t i = 1; i + 1 < c.size() && !changed; ++i) {
      if (passable(c[i - 1], c[i + 1], kMargin_m)) {
        c.erase(c.begin() + static_cast<long>(i));
        changed = true;
        continue;
      }
      if (i + 2 >= c.size() || (c[i + 1] - c[i]).norm() > kMergeCorners_m) continue;
      const Eigen::Vector2d u = c[i] - c[i - 1], v = c[i + 2] - c[i + 1];
      const double det = u.x() * v.y() - u.y() * v.x();
      if (std::abs(det) < 1e-9 * u.norm() * v.norm()) continue;
      const Eigen::Vector2d w = c[i + 1] - c[i - 1];
      const double s = (w.x() * v.y() - w.y() * v.x()) / det;  // crossing at c[i-1] + s u
      const double t = (w.x() * u.y() - w.y() * u.x()) / det;  //          = c[i+1] + t v
      const Eigen::Vector2d x = c[i - 1] + s * u;
      // Ahead of c[i-1], before c[i+2], and near the two corners it replaces.
      if (s <= 0.0 || t >= 1.0 || (x - c[i]).norm() > kMergeCorners_m || (x - c[i + 1]).norm() > kMergeCorners_m)
        continue;
      // Half the margin: the crossing of two lines that graze the same obstacle at the full
      // margin runs a hair closer to it between the grid points they were pulled to.
      if (!passable(c[i - 1], x, kMargin_m / 2) || !passable(x, c[i + 2], kMargin_m / 2)) continue;
      c[i] = x;
      c.erase(c.begin() + static_cast<long>(i) + 1);
      changed = true;
    }
  }
  return c;
}

bool FreeSpace::indoors(const Eigen::Vector2d& p) const {
  // In a room, or in a doorway: within a wall's thickness of one.
  if (rooms_.at(p)) return true;
  for (const auto& [dx, dy] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}})
    if (rooms_.at(p + kDoorway_m * Eigen::Vector2d(dx, dy))) return true;
  return false;
}

bool FreeSpace::passable(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double margin_m) const {
  if (indoors_only_) {
    const int steps = static_cast<int>(std::ceil((b - a).norm() / kCell_m));
    for (int k = 0; k <= steps; ++k)
      if (!indoors(a + (b - a) * (steps == 0 ? 0.0 : double(k) / steps))) return false;
  }
  return segmentClear(a, b, margin_m);
}

void FreeSpace::useRule(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  // Tours stay in the building (the localizer knows rooms, not the street): out of doors only
  // when a or b is.
  const bool indoors_only = indoors(a) && indoors(b);
  if (indoors_only != indoors_only_) {
    indoors_only_ = indoors_only;
    grid_.edges.clear();  // cached for the other rule
  }
}

int FreeSpace::joinGrid(const Eigen::Vector2d& p) const {
  // The nearest grid point reached by a clear segment (with the margin if possible: a start
  // given close to a wall may not allow it).
  const int c = cellNear(p);
  if (c < 0) return -1;
  std::vector<std::pair<double, int>> near;
  for (int d = -1; d < 8; ++d) {
    const int x = c % grid_.nx + (d < 0 ? 0 : kDx[d]), y = c / grid_.nx + (d < 0 ? 0 : kDy[d]);
    if (x >= 0 && y >= 0 && x < grid_.nx && y < grid_.ny) near.emplace_back((centre(y * grid_.nx + x) - p).norm(), y * grid_.nx + x);
  }
  std::sort(near.begin(), near.end());
  for (const double margin : {kMargin_m, 0.0})
    for (const auto& [d, cell] : near)
      if (segmentClear(p, centre(cell), margin)) return cell;
  return -1;
}

std::vector<Eigen::Vector2d> FreeSpace::corners(const Eigen::Vector2d& a, const std::vector<int>& cells,
                                                const Eigen::Vector2d& b) const {
  std::vector<Eigen::Vector2d> points{a};
  for (const int c : cells)
    if ((centre(c) - points.back()).norm() > 1e-9) points.push_back(centre(c));
  if ((b - points.back()).norm() > 1e-9) points.push_back(b);
  return straighten(pullTaut(points));
}

std::vector<Eigen::Vector2d> FreeSpace::path(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  useRule(a, b);
  if (passable(a, b, kMargin_m)) return {a, b};
  if (grid_.edges.size() == 0) makeGrid(a, b);
  const int from = joinGrid(a), to = joinGrid(b);
  if (from < 0 || to < 0) return {};
  const std::vector<int> cells = aStar(from, to);
  if (cells.empty()) return {};
  return corners(a, cells, b);
}

std::vector<Eigen::Vector2d> FreeSpace::pathInto(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                                 const bim::Polygon2& area) {
  useRule(a, b);
  if (passable(a, b, kMargin_m)) return {a, b};
  if (grid_.edges.size() == 0) makeGrid(a, b);
  const int from = joinGrid(a);
  if (from < 0) return {};
  // b off the grid's free cells (to = -1): A* closes the whole component of `from`.
  const int to = joinGrid(b);
  ChunkedCells<std::uint8_t> reached;
  const std::vector<int> cells = aStar(from, to, &reached);
  if (!cells.empty()) return corners(a, cells, b);
  // The reached cell inside the area nearest b: every reached cell's centre is the end of a
  // clear sweep with the margin, so the body fits there.
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  reached.forEachWritten([&](std::size_t c, std::uint8_t is_reached) {
    if (!is_reached) return;
    const Eigen::Vector2d q = centre(static_cast<int>(c));
    const double d = (q - b).norm();
    if (d < best_d && bim::pointInPolygon(area, q)) best_d = d, best = static_cast<int>(c);
  });
  if (best < 0) return {};
  return corners(a, aStar(from, best), centre(best));
}

}  // namespace bimloc::sim
