// The plan's walls as the oracle sees them: the wall faces cut by a height band, as 2D
// segments, and the distance to the nearest of them, exact at every point (each square of a
// raster lists the segments that can be nearest anywhere in it), with a min-pyramid of each
// square's least distance that bounds the field from below over any box: what the
// branch-and-bound's bound needs (sim/oracle/place_search.hpp).
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

// The squared distance from p to the segment (DistanceField::at takes the root of the least).
inline double segmentDistance2(const Eigen::Vector2d& p, const Segment2& s) {
  const Eigen::Vector2d ab = s.b - s.a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - s.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (s.a + t * ab - p).squaredNorm();
}

// The least distance from the square [lo, hi] to the segment: 0 where they meet, else the least
// of the segment's ends to the square and the square's corners to the segment (two disjoint
// convex polygons are nearest at a vertex of one of them).
double squareDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Segment2& s);

// Every wall face of `storey` that reaches into [z_low, z_high] (world z), as a segment at its
// base; a face's openings that span the whole band (doorways) cut it. With `wall_of`, also each
// segment's wall (its index in storey.walls): what one site deviation stands for (docs/oracle.md).
std::vector<Segment2> wallSegmentsInBand(const bim::Storey& storey, double z_low, double z_high,
                                         std::vector<int>* wall_of = nullptr);

class DistanceField {
 public:
  // The raster covers the segments' extent grown by margin_m (at least clamp and a cell).
  DistanceField(const std::vector<Segment2>& walls, double cell_m, double clamp_m, double margin_m);

  // The exact distance from p to the nearest wall segment, at most clamp (and clamp outside the
  // raster): the least distance over every segment, to the bit. Why exact: an
  // interpolated raster is biased by up to half a cell next to a wall, by an amount that depends
  // on where the wall falls between cell centres, so two twin rooms a non-whole number of cells
  // apart scored 5-6 nats apart on one scan of an L room (tests/test_oracle_field.cpp).
  float at(float x, float y) const;
  // The segment nearest to p (the first of equals), or -1 where every one is beyond clamp.
  int nearest(float x, float y) const;
  // A lower bound of at() over the box [x0, x1] x [y0, y1], as a code: the least distance over
  // the raster squares that cover the box, in units of clamp / 255 rounded down. What the
  // branch-and-bound's inner loop reads: a table lookup per point instead of a search
  // (PointModel::boundOfCode).
  std::uint8_t minCodeOver(float x0, float y0, float x1, float y1) const;
  float codeDistance(std::uint8_t code) const { return static_cast<float>(code) * clamp_ / 255.0f; }

  float clamp() const { return clamp_; }
  const Eigen::Vector2d& lower() const { return lower_; }  // the raster's extent
  const Eigen::Vector2d& upper() const { return upper_; }
  std::size_t bytes() const;

 private:
  // Square (i, j) of the raster: [lower + (i, j) cell, lower + (i + 1, j + 1) cell]; the
  // segments that can be nearest in it are candidates_[first_[k] .. first_[k + 1]).
  std::size_t squareOf(float x, float y) const;  // or npos, off the raster
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  Eigen::Vector2d lower_, upper_;
  float cell_ = 0.05f, clamp_ = 0.5f;
  int nx_ = 0, ny_ = 0;
  std::vector<Segment2> segments_;
  std::vector<std::uint32_t> first_;       // nx * ny + 1 offsets
  std::vector<std::uint32_t> candidates_;  // segment indices, ascending within a square
  std::vector<std::uint8_t> codes_;  // each square's least distance in units of clamp / 255, rounded down
  float inv_cell_ = 20.0f;
  // levels_[k - 1][j * nx + i]: the least code over squares [i, i + 2^k) x [j, j + 2^k),
  // for k = 1..kLevels.
  static constexpr int kLevels = 7;
  std::vector<std::vector<std::uint8_t>> levels_;
};

// Inline: the search calls these once per point per pose or node.
inline std::size_t DistanceField::squareOf(float x, float y) const {
  const float fx = (x - static_cast<float>(lower_.x())) / cell_, fy = (y - static_cast<float>(lower_.y())) / cell_;
  if (!(std::abs(fx) < 1e6f && std::abs(fy) < 1e6f)) return npos;  // far off the raster (or not finite)
  const int i = floorIndex(fx), j = floorIndex(fy);
  if (i < 0 || j < 0 || i >= nx_ - 1 || j >= ny_ - 1) return npos;
  return static_cast<std::size_t>(j) * nx_ + i;
}

inline float DistanceField::at(float x, float y) const {
  const std::size_t k = squareOf(x, y);
  if (k == npos || first_[k] == first_[k + 1]) return clamp_;
  const Eigen::Vector2d p(x, y);
  double least = static_cast<double>(clamp_) * clamp_;
  for (std::uint32_t c = first_[k]; c < first_[k + 1]; ++c) least = std::min(least, segmentDistance2(p, segments_[candidates_[c]]));
  // sqrt and the float rounding are monotone: the least of the distances, to the bit.
  return std::min(clamp_, static_cast<float>(std::sqrt(least)));
}

inline std::uint8_t DistanceField::minCodeOver(float x0, float y0, float x1, float y1) const {
  // The squares the box's points lie in: floor((p - lower) / cell) over the box. They are found
  // by multiplying with 1 / cell, which may round across a square's edge: the box is grown by a
  // thousandth of a cell each way first, so that none is missed (at() finds a point's nearest
  // segment whichever of two neighbouring squares it is put in: their lists hold every segment
  // that can be nearest within a millimetre of them). at() is clamp wherever p leaves the
  // raster: only the squares inside count. Four blocks of side 2^k > size / 2 at the box's
  // corners cover it.
  const float lx = static_cast<float>(lower_.x()), ly = static_cast<float>(lower_.y());
  const float fx0 = (x0 - lx) * inv_cell_ - 1e-3f, fx1 = (x1 - lx) * inv_cell_ + 1e-3f;
  const float fy0 = (y0 - ly) * inv_cell_ - 1e-3f, fy1 = (y1 - ly) * inv_cell_ + 1e-3f;
  if (!(fx0 > -1e6f && fy0 > -1e6f && fx1 < 1e6f && fy1 < 1e6f)) return 0;  // no useful bound: the least
  const int i0 = std::max(floorIndex(fx0), 0), i1 = std::min(floorIndex(fx1), nx_ - 1);
  const int j0 = std::max(floorIndex(fy0), 0), j1 = std::min(floorIndex(fy1), ny_ - 1);
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
