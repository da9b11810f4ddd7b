#include "plan_checks.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <map>
#include <tuple>

namespace bimloc::test {
namespace {

using worldgen::StoreySpec;
using worldgen::WallSpec;

constexpr double kJamb_m = 0.05;  // the IFC writer's door lining

struct Frame {  // a wall's axis frame
  Eigen::Vector2d origin, along, across;
  double length;
};

Frame frameOf(const WallSpec& w) {
  const Eigen::Vector2d u = (w.end - w.start).normalized();
  return {w.start, u, Eigen::Vector2d(-u.y(), u.x()), (w.end - w.start).norm()};
}

int roomAt(const StoreySpec& storey, const Eigen::Vector2d& p) {
  for (std::size_t r = 0; r < storey.rooms.size(); ++r)
    if (bim::pointInPolygon(storey.rooms[r].footprint, p)) return static_cast<int>(r);
  return -1;
}

// [x0, y0, x1, y1] of a box along a wall, from `a` to `b` along it.
std::array<double, 4> boxAlong(const WallSpec& w, double a, double b) {
  const Frame f = frameOf(w);
  double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
  for (double s : {a, b})
    for (double side : {-0.5, 0.5}) {
      const Eigen::Vector2d p = f.origin + s * f.along + side * w.thickness_m * f.across;
      x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y()), x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
    }
  return {x0, y0, x1, y1};
}

}  // namespace

std::vector<std::pair<int, int>> doorRooms(const StoreySpec& storey) {
  std::vector<std::pair<int, int>> out;
  for (const auto& d : storey.doors) {
    const WallSpec& w = storey.walls.at(d.wall);
    const Frame f = frameOf(w);
    const Eigen::Vector2d c = f.origin + d.offset_m * f.along, step = (w.thickness_m / 2 + 0.05) * f.across;
    out.emplace_back(roomAt(storey, c + step), roomAt(storey, c - step));
  }
  return out;
}

std::vector<bool> roomsReachedOnFoot(const StoreySpec& storey, int from, double radius_m) {
  constexpr double kCell = 0.05;
  Eigen::Vector2d lo = storey.outline.front(), hi = lo;
  for (const auto& p : storey.outline) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const int nx = static_cast<int>((hi.x() - lo.x()) / kCell) + 1, ny = static_cast<int>((hi.y() - lo.y()) / kCell) + 1;
  const auto centre = [&](int i, int j) { return Eigen::Vector2d(lo.x() + (i + 0.5) * kCell, lo.y() + (j + 0.5) * kCell); };
  std::vector<char> blocked(static_cast<std::size_t>(nx) * ny, 0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) blocked[i + nx * j] = !bim::pointInPolygon(storey.outline, centre(i, j));
  // The solid parts of each wall: between its openings, plus the jambs inside them.
  for (std::size_t k = 0; k < storey.walls.size(); ++k) {
    const WallSpec& w = storey.walls[k];
    const Frame f = frameOf(w);
    std::vector<std::pair<double, double>> open;
    for (const auto& d : storey.doors)
      if (d.wall == static_cast<int>(k)) open.emplace_back(d.offset_m - d.width_m / 2 + kJamb_m, d.offset_m + d.width_m / 2 - kJamb_m);
    std::sort(open.begin(), open.end());
    std::vector<std::pair<double, double>> solid;
    double s = 0.0;
    for (const auto& [a, b] : open) solid.emplace_back(s, a), s = b;
    solid.emplace_back(s, f.length);
    for (const auto& [a, b] : solid) {
      const auto box = boxAlong(w, a, b);
      const int i0 = std::max(0, static_cast<int>((box[0] - radius_m - lo.x()) / kCell) - 1);
      const int i1 = std::min(nx - 1, static_cast<int>((box[2] + radius_m - lo.x()) / kCell) + 1);
      const int j0 = std::max(0, static_cast<int>((box[1] - radius_m - lo.y()) / kCell) - 1);
      const int j1 = std::min(ny - 1, static_cast<int>((box[3] + radius_m - lo.y()) / kCell) + 1);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const Eigen::Vector2d p = centre(i, j);
          const double dx = std::max({box[0] - p.x(), 0.0, p.x() - box[2]}), dy = std::max({box[1] - p.y(), 0.0, p.y() - box[3]});
          if (dx * dx + dy * dy <= radius_m * radius_m) blocked[i + nx * j] = 1;
        }
    }
  }
  std::vector<char> reached(blocked.size(), 0);
  std::deque<int> queue;
  for (int c = 0; c < nx * ny && queue.empty(); ++c)
    if (!blocked[c] && bim::pointInPolygon(storey.rooms.at(from).footprint, centre(c % nx, c / nx))) queue.push_back(c), reached[c] = 1;
  while (!queue.empty()) {
    const int c = queue.front();
    queue.pop_front();
    const int i = c % nx, j = c / nx;
    for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int a = i + di, b = j + dj, n = a + nx * b;
      if (a < 0 || b < 0 || a >= nx || b >= ny || blocked[n] || reached[n]) continue;
      reached[n] = 1;
      queue.push_back(n);
    }
  }
  std::vector<bool> out(storey.rooms.size(), false);
  for (int c = 0; c < nx * ny; ++c)
    if (reached[c]) {
      const int r = roomAt(storey, centre(c % nx, c / nx));
      if (r >= 0) out[r] = true;
    }
  return out;
}

std::vector<SymmetryCount> symmetryCounts(const StoreySpec& storey) {
  std::vector<std::array<double, 4>> boxes;
  for (const auto& w : storey.walls) boxes.push_back(boxAlong(w, 0.0, (w.end - w.start).norm()));
  for (const auto& d : storey.doors) boxes.push_back(boxAlong(storey.walls.at(d.wall), d.offset_m - d.width_m / 2, d.offset_m + d.width_m / 2));
  Eigen::Vector2d lo = storey.outline.front(), hi = lo;
  for (const auto& p : storey.outline) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Eigen::Vector2d sum = lo + hi;
  std::vector<SymmetryCount> out;
  for (const auto& [name, fx, fy] : {std::tuple{"180 deg turn", true, true}, {"mirror x", true, false}, {"mirror y", false, true}}) {
    int unmatched = 0;
    for (const auto& b : boxes) {
      const std::array<double, 4> m = {fx ? sum.x() - b[2] : b[0], fy ? sum.y() - b[3] : b[1], fx ? sum.x() - b[0] : b[2],
                                        fy ? sum.y() - b[1] : b[3]};
      const bool found = std::any_of(boxes.begin(), boxes.end(), [&](const auto& o) {
        for (int k = 0; k < 4; ++k)
          if (std::abs(o[k] - m[k]) > 0.01) return false;
        return true;
      });
      unmatched += found ? 0 : 1;
    }
    out.push_back({name, unmatched});
  }
  return out;
}

int longestIdenticalRow(const StoreySpec& storey) {
  // A rectangular room's key: its size and its doors relative to its lower-left corner, in mm.
  const auto doors = doorRooms(storey);
  std::map<std::vector<long>, std::vector<Eigen::Vector2d>> copies;
  for (std::size_t r = 0; r < storey.rooms.size(); ++r) {
    const bim::Polygon2 poly = bim::simplifyPolygon(storey.rooms[r].footprint);
    if (poly.size() != 4) continue;
    Eigen::Vector2d lo = poly.front(), hi = lo;
    for (const auto& p : poly) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    std::vector<long> key = {std::lround((hi - lo).x() * 1000), std::lround((hi - lo).y() * 1000)};
    std::vector<std::pair<long, long>> at;
    for (std::size_t k = 0; k < doors.size(); ++k) {
      if (doors[k].first != static_cast<int>(r) && doors[k].second != static_cast<int>(r)) continue;
      const auto& d = storey.doors[k];
      const Frame f = frameOf(storey.walls[d.wall]);
      const Eigen::Vector2d c = f.origin + d.offset_m * f.along - lo;
      at.emplace_back(std::lround(c.x() * 1000), std::lround(c.y() * 1000));
    }
    std::sort(at.begin(), at.end());
    for (const auto& [x, y] : at) key.push_back(x), key.push_back(y);
    copies[key].push_back(lo);
  }
  int best = 0;
  for (auto& [key, corners] : copies)
    for (int axis = 0; axis < 2; ++axis) {  // same y (a row along x), or same x
      std::map<long, std::vector<double>> lines;
      for (const auto& c : corners) lines[std::lround(c[1 - axis] * 1000)].push_back(c[axis]);
      for (auto& [line, along] : lines) {
        std::sort(along.begin(), along.end());
        int run = 1;
        for (std::size_t k = 1; k < along.size(); ++k) {
          const bool same_pitch = k >= 2 && std::abs((along[k] - along[k - 1]) - (along[k - 1] - along[k - 2])) < 1e-3;
          run = k == 1 || same_pitch ? run + 1 : 2;
          best = std::max(best, run);
        }
        best = std::max(best, std::min<int>(1, static_cast<int>(along.size())));
      }
    }
  return best;
}

}  // namespace bimloc::test
