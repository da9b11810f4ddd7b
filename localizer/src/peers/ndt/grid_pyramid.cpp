#include "peers/ndt/grid_pyramid.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::peers {

OccupancyGrid OccupancyGrid::fromPoints(const Cloud2& points, double resolution_m, double padding_m) {
  OccupancyGrid g;
  g.resolution_m = resolution_m;
  if (points.empty() || !(resolution_m > 0)) return g;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = Eigen::Vector2d::Constant(-1e300);
  for (const auto& p : points) lo = lo.cwiseMin(p.cast<double>()), hi = hi.cwiseMax(p.cast<double>());
  g.origin = lo - Eigen::Vector2d::Constant(padding_m);
  g.width = static_cast<int>(std::floor((hi.x() + padding_m - g.origin.x()) / resolution_m)) + 1;
  g.height = static_cast<int>(std::floor((hi.y() + padding_m - g.origin.y()) / resolution_m)) + 1;
  g.cells.assign(static_cast<std::size_t>(g.width) * g.height, 0);
  for (const auto& p : points) {
    const int x = static_cast<int>(std::floor((p.x() - g.origin.x()) / resolution_m));
    const int y = static_cast<int>(std::floor((p.y() - g.origin.y()) / resolution_m));
    if (x >= 0 && y >= 0 && x < g.width && y < g.height) g.cells[y * g.width + x] = 1;
  }
  return g;
}

int OccupancyGrid::occupiedCount() const { return static_cast<int>(std::count(cells.begin(), cells.end(), 1)); }

GridPyramid::GridPyramid(const OccupancyGrid& base, int levels) : width_(base.width), height_(base.height) {
  levels_.resize(std::max(1, levels));
  Level& l0 = levels_[0];
  l0.width = base.width, l0.height = base.height, l0.cells = base.cells;
  for (int h = 1; h < static_cast<int>(levels_.size()); ++h) {
    const int w = 1 << (h - 1);  // the window of level h - 1
    Level& l = levels_[h];
    l.pad = (1 << h) - 1;
    l.width = width_ + l.pad, l.height = height_ + l.pad;
    l.cells.assign(static_cast<std::size_t>(l.width) * l.height, 0);
    // [x, x + 2w) = [x, x + w) u [x + w, x + 2w), likewise in y.
    for (int y = -l.pad; y < height_; ++y)
      for (int x = -l.pad; x < width_; ++x)
        l.cells[(y + l.pad) * l.width + (x + l.pad)] =
            std::max({at(h - 1, x, y), at(h - 1, x + w, y), at(h - 1, x, y + w), at(h - 1, x + w, y + w)});
  }
}

}  // namespace bimloc::peers
