#include "walk_grid.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <utility>

namespace bimloc::guide::detail {

WalkGrid::WalkGrid(const std::vector<Segment2>& walls, double clearance_m, double cell_m) : cell_m_(cell_m) {
  if (walls.empty() || !(cell_m > 0.0)) return;
  Eigen::Vector2d lo = walls.front().a, hi = lo;
  for (const auto& s : walls) lo = lo.cwiseMin(s.a).cwiseMin(s.b), hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  origin_ = lo - Eigen::Vector2d::Constant(2.0 * cell_m_);
  nx_ = static_cast<int>(std::ceil((hi.x() - origin_.x()) / cell_m_)) + 3;
  ny_ = static_cast<int>(std::ceil((hi.y() - origin_.y()) / cell_m_)) + 3;
  free_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), 1);
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
        if (distanceTo(s, c) < clearance_m) free_[static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(ix)] = 0;
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
  int sx = 0, sy = 0;
  if (!cell(p, sx, sy) || !(max_m > 0.0)) return d;
  const int reach = static_cast<int>(std::ceil(max_m / cell_m_)) + 1;
  d.x0 = std::max(0, sx - reach), d.y0 = std::max(0, sy - reach);
  d.nx = std::min(nx_, sx + reach + 1) - d.x0, d.ny = std::min(ny_, sy + reach + 1) - d.y0;
  d.metres.assign(static_cast<std::size_t>(d.nx) * static_cast<std::size_t>(d.ny), std::numeric_limits<float>::infinity());
  const auto index = [&](int ix, int iy) {
    return static_cast<std::size_t>(iy - d.y0) * static_cast<std::size_t>(d.nx) + static_cast<std::size_t>(ix - d.x0);
  };
  const auto inside = [&](int ix, int iy) { return ix >= d.x0 && iy >= d.y0 && ix < d.x0 + d.nx && iy < d.y0 + d.ny; };
  using Entry = std::pair<float, std::pair<int, int>>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  // The start: its own cell, or every free cell within snap_m, at its straight distance.
  const int snap = static_cast<int>(std::ceil(snap_m / cell_m_));
  for (int iy = sy - snap; iy <= sy + snap; ++iy)
    for (int ix = sx - snap; ix <= sx + snap; ++ix) {
      if (!inside(ix, iy) || !freeCell(ix, iy)) continue;
      const double r = cell_m_ * std::hypot(ix - sx, iy - sy);
      if (r > snap_m && !(ix == sx && iy == sy)) continue;
      if (static_cast<float>(r) < d.metres[index(ix, iy)]) {
        d.metres[index(ix, iy)] = static_cast<float>(r);
        open.push({static_cast<float>(r), {ix, iy}});
      }
    }
  // Dijkstra over the 8-neighbourhood (a step's length: 1 or sqrt 2 cells).
  while (!open.empty()) {
    const auto [dist, at] = open.top();
    open.pop();
    if (dist > d.metres[index(at.first, at.second)]) continue;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int ix = at.first + dx, iy = at.second + dy;
        if ((dx == 0 && dy == 0) || !inside(ix, iy) || !freeCell(ix, iy)) continue;
        // A diagonal step must not cut a blocked corner.
        if (dx != 0 && dy != 0 && (!freeCell(at.first + dx, at.second) || !freeCell(at.first, at.second + dy))) continue;
        const float next = dist + static_cast<float>(cell_m_ * ((dx != 0 && dy != 0) ? M_SQRT2 : 1.0));
        if (next > max_m || next >= d.metres[index(ix, iy)]) continue;
        d.metres[index(ix, iy)] = next;
        open.push({next, {ix, iy}});
      }
  }
  return d;
}

double WalkGrid::distance(const Distances& d, const Eigen::Vector2d& p) const {
  int ix = 0, iy = 0;
  if (!cell(p, ix, iy) || ix < d.x0 || iy < d.y0 || ix >= d.x0 + d.nx || iy >= d.y0 + d.ny) return std::numeric_limits<double>::infinity();
  return d.metres[static_cast<std::size_t>(iy - d.y0) * static_cast<std::size_t>(d.nx) + static_cast<std::size_t>(ix - d.x0)];
}

}  // namespace bimloc::guide::detail
