// The plan's walls as the oracle sees them: the wall faces cut by a height band, as 2D
// segments, and their distance field on a raster (exact distances at cell centres, clamped,
// bilinear between), with a min-pyramid that bounds the field from below over any box: what
// the branch-and-bound's bound needs (sim/oracle/place_search.hpp).
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace bimloc::sim::oracle {

struct Segment2 {
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
};

// Every wall face of `storey` that reaches into [z_low, z_high] (world z), as a segment at its
// base; a face's openings that span the whole band (doorways) cut it.
std::vector<Segment2> wallSegmentsInBand(const bim::Storey& storey, double z_low, double z_high);

class DistanceField {
 public:
  // The raster covers the segments' extent grown by margin_m.
  DistanceField(const std::vector<Segment2>& walls, double cell_m, double clamp_m, double margin_m);

  // Distance to the nearest wall at p, bilinear between cell centres, at most clamp (and clamp
  // outside the raster).
  float at(float x, float y) const;
  // A lower bound of at() over the box [x0, x1] x [y0, y1]: the least cell value among the cells
  // whose centres surround any point of the box.
  float minOver(float x0, float y0, float x1, float y1) const;

  float clamp() const { return clamp_; }
  const Eigen::Vector2d& lower() const { return lower_; }  // the raster's extent
  const Eigen::Vector2d& upper() const { return upper_; }
  std::size_t bytes() const;

 private:
  float cell(int i, int j) const { return values_[static_cast<std::size_t>(j) * nx_ + i]; }
  Eigen::Vector2d lower_, upper_;
  float cell_ = 0.05f, clamp_ = 0.5f;
  int nx_ = 0, ny_ = 0;
  std::vector<float> values_;  // cell (i, j) centre at lower + (i, j) * cell
  // levels_[k - 1][j * nx + i]: the least value over cells [i, i + 2^k) x [j, j + 2^k), in
  // units of clamp / 255 rounded down (a lower bound), for k = 1..kLevels.
  static constexpr int kLevels = 7;
  std::vector<std::vector<std::uint8_t>> levels_;
};

}  // namespace bimloc::sim::oracle
