// The plan's walls as the oracle sees them: the wall faces cut by a height band, as 2D
// segments, and their distance field on a raster (exact distances at cell centres, clamped,
// bilinear between), with a min-pyramid that bounds the field from below over any box: what
// the branch-and-bound's bound needs (sim/oracle/place_search.hpp).
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace bimloc::sim::oracle {

// floor(v) for |v| < 2^20, exactly (v is a float, exact in double): std::floor is a libm call
// on the baseline x86-64 this is built for, and these run once per point per node.
inline int floorIndex(float v) { return static_cast<int>(static_cast<double>(v) + 1048576.0) - 1048576; }


struct Segment2 {
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
};

// The distance from p to the segment.
float segmentDistance(const Eigen::Vector2d& p, const Segment2& s);

// Calls f(index, distance) for each cell of a raster (origin `lower`, side cell_m, nx x ny,
// row-major) whose centre lies in the segment's box grown by reach_m: its exact distance to it.
template <typename F>
void forCellsNear(const Segment2& s, const Eigen::Vector2d& lower, double cell_m, double reach_m, int nx, int ny, F&& f) {
  const Eigen::Vector2d lo = s.a.cwiseMin(s.b).array() - reach_m, hi = s.a.cwiseMax(s.b).array() + reach_m;
  const int i0 = std::max(0, static_cast<int>(std::floor((lo.x() - lower.x()) / cell_m)));
  const int i1 = std::min(nx - 1, static_cast<int>(std::ceil((hi.x() - lower.x()) / cell_m)));
  const int j0 = std::max(0, static_cast<int>(std::floor((lo.y() - lower.y()) / cell_m)));
  const int j1 = std::min(ny - 1, static_cast<int>(std::ceil((hi.y() - lower.y()) / cell_m)));
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) f(static_cast<std::size_t>(j) * nx + i, segmentDistance(lower + cell_m * Eigen::Vector2d(i, j), s));
}

// Every wall face of `storey` that reaches into [z_low, z_high] (world z), as a segment at its
// base; a face's openings that span the whole band (doorways) cut it. With `wall_of`, also each
// segment's wall (its index in storey.walls): what one site deviation stands for (docs/oracle.md).
std::vector<Segment2> wallSegmentsInBand(const bim::Storey& storey, double z_low, double z_high,
                                         std::vector<int>* wall_of = nullptr);

class DistanceField {
 public:
  // The raster covers the segments' extent grown by margin_m.
  DistanceField(const std::vector<Segment2>& walls, double cell_m, double clamp_m, double margin_m);

  // Distance to the nearest wall at p, bilinear between cell centres, at most clamp (and clamp
  // outside the raster).
  float at(float x, float y) const;
  // A lower bound of at() over the box [x0, x1] x [y0, y1], as a code: the least value among the
  // cells whose centres surround any point of the box, in units of clamp / 255 rounded down.
  // What the branch-and-bound's inner loop reads: a table lookup per point instead of a division
  // and a search (PointModel::boundOfCode).
  std::uint8_t minCodeOver(float x0, float y0, float x1, float y1) const;
  float codeDistance(std::uint8_t code) const { return static_cast<float>(code) * clamp_ / 255.0f; }

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
  std::vector<std::uint8_t> codes_;  // values_ in units of clamp / 255, rounded down
  float inv_cell_ = 20.0f;
  // levels_[k - 1][j * nx + i]: the least value over cells [i, i + 2^k) x [j, j + 2^k), in
  // units of clamp / 255 rounded down (a lower bound), for k = 1..kLevels.
  static constexpr int kLevels = 7;
  std::vector<std::vector<std::uint8_t>> levels_;
};

// Inline: the search calls these once per point per pose or node.
inline float DistanceField::at(float x, float y) const {
  const float fx = (x - static_cast<float>(lower_.x())) / cell_, fy = (y - static_cast<float>(lower_.y())) / cell_;
  if (!(std::abs(fx) < 1e6f && std::abs(fy) < 1e6f)) return clamp_;  // far off the raster (or not finite)
  const int i = floorIndex(fx), j = floorIndex(fy);
  if (i < 0 || j < 0 || i >= nx_ - 1 || j >= ny_ - 1) return clamp_;
  const float u = fx - static_cast<float>(i), v = fy - static_cast<float>(j);
  const float* row = &values_[static_cast<std::size_t>(j) * nx_ + i];
  const float* next = row + nx_;
  return (1 - v) * ((1 - u) * row[0] + u * row[1]) + v * ((1 - u) * next[0] + u * next[1]);
}

inline std::uint8_t DistanceField::minCodeOver(float x0, float y0, float x1, float y1) const {
  // Cells whose centres surround a point p: floor((p - lower) / cell) and the next one. They are
  // found by multiplying with 1 / cell, which may round across a cell's edge: the box is grown by
  // a thousandth of a cell each way first, so that no such cell is missed (one more, at worst: a
  // bound a little looser, never wrong). at() is clamp wherever its cells leave the raster: only
  // the cells inside count. Four squares of side 2^k > size / 2 at the box's corners cover it.
  const float lx = static_cast<float>(lower_.x()), ly = static_cast<float>(lower_.y());
  const float fx0 = (x0 - lx) * inv_cell_ - 1e-3f, fx1 = (x1 - lx) * inv_cell_ + 1e-3f;
  const float fy0 = (y0 - ly) * inv_cell_ - 1e-3f, fy1 = (y1 - ly) * inv_cell_ + 1e-3f;
  if (!(fx0 > -1e6f && fy0 > -1e6f && fx1 < 1e6f && fy1 < 1e6f)) return 0;  // no useful bound: the least
  const int i0 = std::max(floorIndex(fx0), 0), i1 = std::min(floorIndex(fx1) + 1, nx_ - 1);
  const int j0 = std::max(floorIndex(fy0), 0), j1 = std::min(floorIndex(fy1) + 1, ny_ - 1);
  if (i0 > i1 || j0 > j1) return 255;  // wholly off the raster: clamp
  const int size = std::max(i1 - i0 + 1, j1 - j0 + 1);
  if (size == 1) return codes_[static_cast<std::size_t>(j0) * nx_ + i0];
  const int k = 31 - __builtin_clz(static_cast<unsigned>(size));  // 2^k <= size < 2^(k+1)
  const int side = 1 << k;
  if (k > kLevels || side > nx_ || side > ny_) return 0;
  const int a0 = std::clamp(i0, 0, nx_ - side), a1 = std::clamp(i1 - side + 1, 0, nx_ - side);
  const int b0 = std::clamp(j0, 0, ny_ - side), b1 = std::clamp(j1 - side + 1, 0, ny_ - side);
  const std::uint8_t* level = levels_[k - 1].data();
  const std::size_t r0 = static_cast<std::size_t>(b0) * nx_, r1 = static_cast<std::size_t>(b1) * nx_;
  return std::min(std::min(level[r0 + a0], level[r0 + a1]), std::min(level[r1 + a0], level[r1 + a1]));
}

}  // namespace bimloc::sim::oracle
