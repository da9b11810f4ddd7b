// AMCL's 2D world: an occupancy grid sliced from the storey mesh (the ROS amcl node gets it from
// map_server; here the plan is the map). Private to the library.
#pragma once

#include <bimloc/bim/building.hpp>
#include <bimloc/peers/amcl_config.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::peers::amcl {

struct Grid {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // map xy of the lower-left corner of cell (0, 0)
  double resolution_m = 0.05;
  int width = 0, height = 0;           // cells along x, along y
  std::vector<std::uint8_t> occupied;  // row-major (y rows), 1 = an obstacle in the band

  Grid() = default;
  Grid(const Eigen::Vector2d& lower, const Eigen::Vector2d& upper, double resolution);
  std::size_t size() const { return occupied.size(); }
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * width + i; }
  bool contains(int i, int j) const { return i >= 0 && j >= 0 && i < width && j < height; }
  // The cell holding map point (x, y) (may be outside the grid).
  Eigen::Vector2i cellOf(double x, double y) const;
  Eigen::Vector2d centre(int i, int j) const { return origin + resolution_m * Eigen::Vector2d(i + 0.5, j + 0.5); }
  std::size_t occupiedCount() const;
  // Marks every cell the segment a-b passes through.
  void markSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  // Marks every cell a convex polygon (map xy) covers, its edges included.
  void markConvex(const std::vector<Eigen::Vector2d>& polygon);
};

// The storey's obstacles between band_min_m and band_max_m above its floor (elevation_m): each
// triangle of the mesh clipped to that slab and drawn from above. Floor and ceiling slabs lie
// outside the band; door leaves are left out unless map_doors. The grid spans the slice, the
// rooms and likelihood_max_dist_m around them.
struct StoreySlice {
  Grid grid;
  std::vector<std::string> warnings;
};
StoreySlice sliceStorey(const bim::Storey& storey, const AmclConfig& config);

// Triangle a, b, c clipped to the slab z0 <= z <= z1, seen from above (empty if it misses).
std::vector<Eigen::Vector2d> clipToSlab(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double z0, double z1);

}  // namespace bimloc::peers::amcl
