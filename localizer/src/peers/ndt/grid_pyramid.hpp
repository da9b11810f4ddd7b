// The 2D map of the global search (hdl_global_localization's OccupancyGridMap): a binary grid
// of the map slice, and above it the pyramid of upper bounds the branch-and-bound prunes with.
#pragma once

#include "peers/ndt/map_cloud.hpp"

#include <cstdint>
#include <vector>

namespace bimloc::peers {

// Cell (x, y) covers [origin + (x, y) * resolution, + resolution); occupied when a map point
// falls in it.
struct OccupancyGrid {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double resolution_m = 0.5;
  int width = 0, height = 0;
  std::vector<std::uint8_t> cells;  // row-major, y * width + x

  // The grid over the points' bounding box grown by padding_m on each side.
  static OccupancyGrid fromPoints(const Cloud2& points, double resolution_m, double padding_m);
  bool occupied(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height && cells[y * width + x]; }
  int occupiedCount() const;
};

// Level h holds, at cell (x, y), the max of the base cells [x, x + 2^h) x [y, y + 2^h) (0 outside
// the grid). A node of the search at level h with translation (tx, ty) stands for every
// translation in [tx, tx + 2^h) x [ty, ty + 2^h); a scan point whose cell offset is o lands in
// one of o + that block, so summing level h at o + (tx, ty) bounds every leaf's score from above.
// This is Cartographer's sliding-window precomputation (Hess et al. 2016, sec. V.C); hdl's 2x2
// max-pooling of disjoint blocks is cheaper but is not a bound for every translation.
class GridPyramid {
 public:
  GridPyramid(const OccupancyGrid& base, int levels);
  int levels() const { return static_cast<int>(levels_.size()); }
  int width() const { return width_; }
  int height() const { return height_; }
  std::uint8_t at(int level, int x, int y) const {
    const Level& l = levels_[level];
    x += l.pad, y += l.pad;
    return x >= 0 && y >= 0 && x < l.width && y < l.height ? l.cells[y * l.width + x] : 0;
  }

 private:
  struct Level {
    int pad = 0, width = 0, height = 0;  // cells [-pad, base width) x [-pad, base height)
    std::vector<std::uint8_t> cells;
  };
  int width_ = 0, height_ = 0;
  std::vector<Level> levels_;
};

}  // namespace bimloc::peers
