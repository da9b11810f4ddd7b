#include "walk_grid.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

namespace bimloc::guide::detail {

WalkGrid::WalkGrid(const std::vector<Segment2>& walls, double clearance_m, double cell_m) : cell_m_(cell_m) {
  if (walls.empty() || !(cell_m > 0.0)) return;
  Eigen::Vector2d lo = walls.front().a, hi = lo;
  for (const auto& s : walls) lo = lo.cwiseMin(s.a).cwiseMin(s.b), hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  origin_ = lo - Eigen::Vector2d::Constant(2.0 * cell_m_);
  nx_ = static_cast<int>(std::ceil((hi.x() - origin_.x()) / cell_m_)) + 3;
  ny_ = static_cast<int>(std::ceil((hi.y() - origin_.y()) / cell_m_)) + 3;
  free_.assign(static_cast<std::size_t>(nx_ + 2) * static_cast<std::size_t>(ny_ + 2), 0);
  for (int iy = 0; iy < ny_; ++iy)
    for (int ix = 0; ix < nx_; ++ix) free_[padded(ix, iy)] = 1;
  // Each wall blocks the cells whose centre lies within the clearance of it: only the cells of
  // its box grown by the clearance are looked at, so the cost is the walls' area, not the floor's.
  for (const auto& s : walls) {
    const Eigen::Vector2d a = s.a.cwiseMin(s.b) - Eigen::Vector2d::Constant(clearance_m);
    const Eigen::Vector2d b = s.a.cwiseMax(s.b) + Eigen::Vector2d::Constant(clearance_m);
    const int ix0 = std::max(0, static_cast<int>(std::floor((a.x() - origin_.x()) / cell_m_)));
    const int iy0 = std::max(0, static_cast<int>(std::floor((a.y() - origin_.y()) / cell_m_)));
    const int ix1 = std::min(nx_ - 1, static_cast<int>(std::floor((b.x() - origin_.x()) / cell_m_)));
    const int iy1 = std::min(ny_ - 1, static_cast<int>(std::floor((b.y() - origin_.y()) / cell_m_)));
    for (int iy = iy0; iy <= iy1; ++iy)
      for (int ix = ix0; ix <= ix1; ++ix) {
        const Eigen::Vector2d c = origin_ + cell_m_ * Eigen::Vector2d(ix + 0.5, iy + 0.5);
        if (distanceTo(s, c) < clearance_m) free_[padded(ix, iy)] = 0;
      }
  }
}

bool WalkGrid::cell(const Eigen::Vector2d& p, int& ix, int& iy) const {
  if (!p.allFinite() || free_.empty()) return false;
  ix = static_cast<int>(std::floor((p.x() - origin_.x()) / cell_m_));
  iy = static_cast<int>(std::floor((p.y() - origin_.y()) / cell_m_));
  return ix >= 0 && iy >= 0 && ix < nx_ && iy < ny_;
}

bool WalkGrid::free(const Eigen::Vector2d& p) const {
  int ix = 0, iy = 0;
  return cell(p, ix, iy) && freeCell(ix, iy);
}

WalkGrid::Distances WalkGrid::from(const Eigen::Vector2d& p, double max_m, double snap_m) const {
  Distances d;
  walk(p, max_m, snap_m, {}, d);
  return d;
}

WalkGrid::Distances WalkGrid::from(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& targets, double max_m, double snap_m) const {
  std::vector<std::pair<int, int>> cells;
  int tx = 0, ty = 0;
  for (const auto& t : targets)
    if (cell(t, tx, ty)) cells.emplace_back(tx, ty);
  Distances d;
  // With no target on the grid, nothing of the walk is read.
  if (!cells.empty()) walk(p, max_m, snap_m, cells, d);
  return d;
}

double WalkGrid::distanceBetween(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double max_m, double snap_m) const {
  int tx = 0, ty = 0;
  if (!cell(b, tx, ty)) return std::numeric_limits<double>::infinity();
  Distances d;
  return walk(a, max_m, snap_m, {{tx, ty}}, d);
}

// Dijkstra over the 8-neighbourhood (a step's length: 1 or sqrt 2 cells), its queue a row of
// buckets half a cell wide (Dial's): a cell is expanded only once every cell nearer by a step
// (at least a cell) has been, so each cell is expanded once, with its final distance, in
// whatever order a bucket holds them. A cell's distance is then the least of its start value
// and its neighbours' final distances plus a step, as a binary heap's order gives it, to the bit.
double WalkGrid::walk(const Eigen::Vector2d& p, double max_m, double snap_m, const std::vector<std::pair<int, int>>& targets,
                      Distances& d) const {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  int sx = 0, sy = 0;
  if (!cell(p, sx, sy) || !(max_m > 0.0)) return kInf;
  const int reach = static_cast<int>(std::ceil(max_m / cell_m_)) + 1;
  d.x0 = std::max(0, sx - reach), d.y0 = std::max(0, sy - reach);
  d.nx = std::min(nx_, sx + reach + 1) - d.x0, d.ny = std::min(ny_, sy + reach + 1) - d.y0;
  d.metres.assign(static_cast<std::size_t>(d.nx) * static_cast<std::size_t>(d.ny), kInf);
  const auto index = [&](int ix, int iy) {
    return static_cast<std::size_t>(iy - d.y0) * static_cast<std::size_t>(d.nx) + static_cast<std::size_t>(ix - d.x0);
  };
  const auto inside = [&](int ix, int iy) { return ix >= d.x0 && iy >= d.y0 && ix < d.x0 + d.nx && iy < d.y0 + d.ny; };
  // The targets the walk can settle (free cells of the window), each once: when none is left,
  // the distances read are final.
  const bool has_targets = !targets.empty();
  std::vector<std::uint8_t> is_target;
  std::size_t remaining = 0, last_target = 0;
  if (has_targets) {
    is_target.assign(d.metres.size(), 0);
    for (const auto& [tx, ty] : targets)
      if (inside(tx, ty) && freeCell(tx, ty) && !is_target[index(tx, ty)]) is_target[index(tx, ty)] = 1, ++remaining, last_target = index(tx, ty);
    if (remaining == 0) return kInf;
  }
  struct Entry {
    float metres;
    int ix, iy;  // in the grid
  };
  const double width = 0.5 * cell_m_;
  const std::size_t buckets_n = static_cast<std::size_t>(std::max(max_m, snap_m) / width) + 2;
  std::vector<std::vector<Entry>> buckets(buckets_n);
  const auto push = [&](float metres, int ix, int iy, std::size_t at_least) {
    const std::size_t b = std::min(buckets_n - 1, std::max(at_least, static_cast<std::size_t>(metres / width)));
    buckets[b].push_back({metres, ix, iy});
  };
  // The start: its own cell, or every free cell within snap_m, at its straight distance.
  const int snap = static_cast<int>(std::ceil(snap_m / cell_m_));
  for (int iy = sy - snap; iy <= sy + snap; ++iy)
    for (int ix = sx - snap; ix <= sx + snap; ++ix) {
      if (!inside(ix, iy) || !freeCell(ix, iy)) continue;
      const double r = cell_m_ * std::hypot(ix - sx, iy - sy);
      if (r > snap_m && !(ix == sx && iy == sy)) continue;
      if (static_cast<float>(r) < d.metres[index(ix, iy)]) {
        d.metres[index(ix, iy)] = static_cast<float>(r);
        push(static_cast<float>(r), ix, iy, 0);
      }
    }
  const float straight = static_cast<float>(cell_m_ * 1.0), diagonal = static_cast<float>(cell_m_ * M_SQRT2);
  // Cells next to a window's cell are on the padded grid (a diagonal's corner may lie just
  // outside the window): no bounds test for them.
  const std::uint8_t* free = free_.data();
  for (std::size_t b = 0; b < buckets_n; ++b) {
    for (std::size_t k = 0; k < buckets[b].size(); ++k) {
      const Entry e = buckets[b][k];
      const std::size_t at = index(e.ix, e.iy);
      if (e.metres > d.metres[at]) continue;
      if (has_targets && is_target[at]) {
        is_target[at] = 0;
        if (--remaining == 0) return e.metres;
      }
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int ix = e.ix + dx, iy = e.iy + dy;
          if ((dx == 0 && dy == 0) || !inside(ix, iy) || !free[padded(ix, iy)]) continue;
          // A diagonal step must not cut a blocked corner.
          if (dx != 0 && dy != 0 && (!free[padded(e.ix + dx, e.iy)] || !free[padded(e.ix, e.iy + dy)])) continue;
          const float next = e.metres + ((dx != 0 && dy != 0) ? diagonal : straight);
          const std::size_t to = index(ix, iy);
          if (next > max_m || next >= d.metres[to]) continue;
          d.metres[to] = next;
          push(next, ix, iy, b);
        }
    }
    std::vector<Entry>().swap(buckets[b]);
  }
  return has_targets ? d.metres[last_target] : kInf;
}

double WalkGrid::distance(const Distances& d, const Eigen::Vector2d& p) const {
  int ix = 0, iy = 0;
  if (!cell(p, ix, iy) || ix < d.x0 || iy < d.y0 || ix >= d.x0 + d.nx || iy >= d.y0 + d.ny) return std::numeric_limits<double>::infinity();
  return d.metres[static_cast<std::size_t>(iy - d.y0) * static_cast<std::size_t>(d.nx) + static_cast<std::size_t>(ix - d.x0)];
}

}  // namespace bimloc::guide::detail
