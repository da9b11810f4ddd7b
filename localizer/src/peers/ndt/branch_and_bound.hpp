// Global localization as hdl_global_localization's BBS does it: the scan slice matched against
// the map's occupancy grid over every translation of the grid and a set of yaws, branch-and-
// bound over the grid pyramid (Hess et al. 2016, "Real-time loop closure in 2D lidar SLAM",
// sec. V). The score of a pose is the number of scan cells landing in occupied map cells.
#pragma once

#include "peers/ndt/grid_pyramid.hpp"

#include <optional>

namespace bimloc::peers {

// A pose of the search: yaw = 2 pi yaw / yaw_count, translation = origin + (x, y) * resolution.
struct GridPose {
  int yaw = 0, x = 0, y = 0;
  int score = -1;
  // The order ties are broken in: the smaller (yaw, x, y) wins among equal scores.
  bool before(int yaw_, int x_, int y_) const { return yaw != yaw_ ? yaw < yaw_ : x != x_ ? x < x_ : y < y_; }
};

// Which poses the search skips (to find the best pose distinct from a first one): those within
// distance_m of `center`'s translation and within angle_rad of its yaw.
struct Exclusion {
  GridPose center;
  double distance_m = 0, angle_rad = 0;
};

struct SearchGrid {
  const OccupancyGrid* grid = nullptr;
  const GridPyramid* pyramid = nullptr;
  int yaw_count = 1;

  double yawOf(int yaw) const;
  Eigen::Vector3d pose(const GridPose& p) const;  // x, y, yaw in the map
  bool excluded(const Exclusion& e, int yaw, int x, int y) const;
};

// hdl_global_localization's angular step: the yaw step that moves a point at max_range_m by one
// cell, acos(1 - r^2 / (2 R^2)); the count of yaws that covers the circle with it.
int yawCount(double resolution_m, double max_range_m);

// One representative point per occupied cell of the scan slice (base frame, the cells of
// resolution_m): the scan's "cells", so that the score counts the outline, not the point density.
Cloud2 scanCells(const Cloud2& slice, double resolution_m);

struct SearchResult {
  GridPose best;         // score -1: no pose (no scan, or every pose excluded)
  long nodes = 0;        // nodes scored (the work done)
};

// Branch-and-bound: depth first from the coarsest level, children in the order of their bound.
SearchResult branchAndBound(const SearchGrid& g, const Cloud2& scan_cells, const Exclusion* exclude = nullptr);

// Every pose of the same grid scored at the finest level: the independent truth of the tests.
SearchResult exhaustiveSearch(const SearchGrid& g, const Cloud2& scan_cells, const Exclusion* exclude = nullptr);

}  // namespace bimloc::peers
