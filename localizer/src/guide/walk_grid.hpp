// The floor as a grid of the cells where the walking body fits (its clearance from every wall
// of the slice, doors as gaps), and walking distances over it. A goal in the corridor seen
// through an office's door is a few metres' walk through the door, not a straight line: with
// straight lines only, a robot in one of two alike offices was never sent out of it (site_office
// R101: 8 m walked in 40 s, the twins never told apart).
#pragma once

#include "wall_slice.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace bimloc::guide::detail {

class WalkGrid {
 public:
  WalkGrid(const std::vector<Segment2>& walls, double clearance_m, double cell_m = 0.1);

  // Walking distances from one point, over a window of the grid around it.
  struct Distances {
    int x0 = 0, y0 = 0, nx = 0, ny = 0;  // the window, in grid cells
    std::vector<float> metres;           // per cell of the window; infinity: not reached
  };
  // From `from` (from the nearest free cell within snap_m when its own has no room for the body:
  // a place's pose is only as good as its fit), every free cell within max_m of walking.
  Distances from(const Eigen::Vector2d& from, double max_m, double snap_m = 0.5) const;
  // The same, with only the cells of `targets` sure to hold their final distance: the walk stops
  // once each of them is settled (the guide reads a place's walk at its trial goals only).
  Distances from(const Eigen::Vector2d& from, const std::vector<Eigen::Vector2d>& targets, double max_m, double snap_m = 0.5) const;
  // distance(from(a, max_m, snap_m), b), the same value, with the walk stopped once b's cell is
  // settled (a goal still under way asks one walk per place at every weighing).
  double distanceBetween(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double max_m, double snap_m = 0.5) const;
  // The walking distance to p (infinity: not free, or not reached).
  double distance(const Distances& d, const Eigen::Vector2d& p) const;
  bool free(const Eigen::Vector2d& p) const;

 private:
  bool cell(const Eigen::Vector2d& p, int& ix, int& iy) const;
  // from() and distanceBetween(): the walk, stopped when every cell of `targets` (grid cells)
  // is settled (none: never). Returns the last one's distance (infinity when not reached or no target).
  double walk(const Eigen::Vector2d& p, double max_m, double snap_m, const std::vector<std::pair<int, int>>& targets, Distances& d) const;
  bool freeCell(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < nx_ && iy < ny_ && free_[padded(ix, iy)]; }
  // free_ holds the grid with a border of one blocked cell: ix in -1 .. nx_, iy in -1 .. ny_.
  std::size_t padded(int ix, int iy) const {
    return static_cast<std::size_t>(iy + 1) * static_cast<std::size_t>(nx_ + 2) + static_cast<std::size_t>(ix + 1);
  }
  double cell_m_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint8_t> free_;
};

}  // namespace bimloc::guide::detail
