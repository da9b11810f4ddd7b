#include "sim/oracle/wall_field.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace bimloc::sim::oracle {
namespace {

// A square's corners.
std::array<Eigen::Vector2d, 4> cornersOf(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  return {lo, Eigen::Vector2d(hi.x(), lo.y()), hi, Eigen::Vector2d(lo.x(), hi.y())};
}

double pointSquareDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  return (p.cwiseMax(lo).cwiseMin(hi) - p).norm();
}

// Whether the segment meets the square (Liang-Barsky: clip its parameter interval to each slab).
bool meets(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Segment2& s) {
  double t0 = 0, t1 = 1;
  const Eigen::Vector2d d = s.b - s.a;
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0) {
      if (s.a[axis] < lo[axis] || s.a[axis] > hi[axis]) return false;
      continue;
    }
    double ta = (lo[axis] - s.a[axis]) / d[axis], tb = (hi[axis] - s.a[axis]) / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

double squareDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Segment2& s) {
  if (meets(lo, hi, s)) return 0.0;
  double d = std::min(pointSquareDistance(s.a, lo, hi), pointSquareDistance(s.b, lo, hi));
  for (const auto& c : cornersOf(lo, hi)) d = std::min(d, std::sqrt(segmentDistance2(c, s)));
  return d;
}

std::vector<Segment2> wallSegmentsInBand(const bim::Storey& storey, double z_low, double z_high, std::vector<int>* wall_of) {
  std::vector<Segment2> out;
  if (wall_of) wall_of->clear();
  for (std::size_t w = 0; w < storey.walls.size(); ++w)
    for (const auto& face : storey.walls[w].faces) {
      const auto& wall = storey.walls[w];
      const double z0 = face.start.z(), z1 = z0 + wall.height_m, length = face.length_m();
      if (z1 <= z_low || z0 >= z_high || length <= 0) continue;
      // Doorways: openings spanning the whole band leave no surface in it.
      std::vector<std::pair<double, double>> cuts;
      for (const auto& o : face.openings)
        if (o.z_min_m <= z_low && o.z_max_m >= z_high) cuts.emplace_back(o.along_min_m, o.along_max_m);
      std::sort(cuts.begin(), cuts.end());
      const Eigen::Vector2d a = face.start.head<2>(), u = (face.end - face.start).head<2>() / length;
      double from = 0;
      for (const auto& [lo, hi] : cuts) {
        if (lo > from) out.push_back({a + from * u, a + std::min(lo, length) * u});
        from = std::max(from, hi);
      }
      if (from < length) out.push_back({a + from * u, a + length * u});
      if (wall_of) wall_of->resize(out.size(), static_cast<int>(w));
    }
  return out;
}

DistanceField::DistanceField(const std::vector<Segment2>& walls, double cell_m, double clamp_m, double margin_m)
    : cell_(static_cast<float>(cell_m)), clamp_(static_cast<float>(clamp_m)), segments_(walls) {
  lower_ = Eigen::Vector2d::Constant(walls.empty() ? 0.0 : 1e300), upper_ = Eigen::Vector2d::Constant(walls.empty() ? 0.0 : -1e300);
  for (const auto& s : walls) lower_ = lower_.cwiseMin(s.a).cwiseMin(s.b), upper_ = upper_.cwiseMax(s.a).cwiseMax(s.b);
  // At least clamp round the segments: off the raster every point is then beyond clamp, and
  // at() is exact everywhere.
  margin_m = std::max(margin_m, clamp_m + cell_m);
  lower_.array() -= margin_m, upper_.array() += margin_m;
  nx_ = static_cast<int>(std::ceil((upper_.x() - lower_.x()) / cell_m)) + 1;
  ny_ = static_cast<int>(std::ceil((upper_.y() - lower_.y()) / cell_m)) + 1;
  const std::size_t squares = static_cast<std::size_t>(nx_) * ny_;
  // Each square is taken a millimetre larger on every side: a point that float rounding puts in
  // the square next to its own (off by ~1e-5 m) still finds its nearest segment listed.
  const double grow = 1e-3;
  const auto squareAt = [&](std::size_t k, Eigen::Vector2d* lo, Eigen::Vector2d* hi) {
    const auto i = static_cast<double>(k % static_cast<std::size_t>(nx_)), j = static_cast<double>(k / static_cast<std::size_t>(nx_));
    *lo = lower_ + cell_m * Eigen::Vector2d(i, j) - Eigen::Vector2d::Constant(grow);
    *hi = lower_ + cell_m * Eigen::Vector2d(i + 1, j + 1) + Eigen::Vector2d::Constant(grow);
  };
  // The squares that may come within clamp of a segment: those whose lower corner lies in its
  // box grown by clamp and two cells.
  const auto forSquaresNear = [&](const Segment2& s, auto&& f) {
    const double reach = clamp_m + 2 * cell_m;
    const Eigen::Vector2d lo = s.a.cwiseMin(s.b).array() - reach, hi = s.a.cwiseMax(s.b).array() + reach;
    const int i0 = std::max(0, static_cast<int>(std::floor((lo.x() - lower_.x()) / cell_m)));
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::ceil((hi.x() - lower_.x()) / cell_m)));
    const int j0 = std::max(0, static_cast<int>(std::floor((lo.y() - lower_.y()) / cell_m)));
    const int j1 = std::min(ny_ - 1, static_cast<int>(std::ceil((hi.y() - lower_.y()) / cell_m)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) f(static_cast<std::size_t>(j) * nx_ + i);
  };
  // 1. Each square's least distance to any segment, as its code (floor is monotone: the least
  // code is the code of the least), and the least over the segments of the farthest a point of
  // the square can be from it (its farthest corner: the distance to a segment is convex): no
  // segment farther than that from the whole square is ever nearest in it. Kept in float,
  // rounded up (a candidate more, never one less): 5 bytes a square where a large storey has
  // millions of squares.
  const double scale = 255.0 / clamp_m;
  codes_.assign(squares, 255);
  std::vector<float> farthest(squares, std::numeric_limits<float>::infinity());
  for (const auto& s : walls)
    forSquaresNear(s, [&](std::size_t k) {
      Eigen::Vector2d lo, hi;
      squareAt(k, &lo, &hi);
      const auto code = static_cast<std::uint8_t>(std::min(255.0, std::floor(squareDistance(lo, hi, s) * scale)));
      codes_[k] = std::min(codes_[k], code);
      double far = 0;
      for (const auto& c : cornersOf(lo, hi)) far = std::max(far, segmentDistance2(c, s));
      const float up = std::nextafter(static_cast<float>(std::sqrt(far)), std::numeric_limits<float>::infinity());
      farthest[k] = std::min(farthest[k], up);
    });
  // 2. The candidates: the segments within min(farthest, clamp) of the square, ascending (a
  // counting sort by square: the segments arrive in order).
  first_.assign(squares + 1, 0);
  const auto isCandidate = [&](std::size_t k, const Segment2& s) {
    Eigen::Vector2d lo, hi;
    squareAt(k, &lo, &hi);
    return squareDistance(lo, hi, s) <= std::min(static_cast<double>(farthest[k]), clamp_m);
  };
  for (const auto& s : walls)
    forSquaresNear(s, [&](std::size_t k) { first_[k + 1] += isCandidate(k, s); });
  for (std::size_t k = 0; k < squares; ++k) first_[k + 1] += first_[k];
  candidates_.resize(first_[squares]);
  std::vector<std::uint32_t> next(first_.begin(), first_.end() - 1);
  for (std::size_t n = 0; n < walls.size(); ++n)
    forSquaresNear(walls[n], [&](std::size_t k) {
      if (isCandidate(k, walls[n])) candidates_[next[k]++] = static_cast<std::uint32_t>(n);
    });
  // The min-pyramid, quantized downwards (still a lower bound).
  inv_cell_ = 1.0f / cell_;
  levels_.resize(kLevels);
  for (int k = 1; k <= kLevels; ++k) {
    auto& level = levels_[k - 1];
    level.assign(squares, 0);
    const int half = 1 << (k - 1);
    const auto& below = k == 1 ? codes_ : levels_[k - 2];
    const std::size_t dx = half, dy = static_cast<std::size_t>(half) * nx_;
    for (int j = 0; j + 2 * half <= ny_; ++j)
      for (int i = 0; i + 2 * half <= nx_; ++i) {
        const std::size_t at = static_cast<std::size_t>(j) * nx_ + i;
        level[at] = std::min(std::min(below[at], below[at + dx]), std::min(below[at + dy], below[at + dx + dy]));
      }
  }
}

int DistanceField::nearest(float x, float y) const {
  const std::size_t k = squareOf(x, y);
  if (k == npos) return -1;
  const Eigen::Vector2d p(x, y);
  double least = static_cast<double>(clamp_) * clamp_;
  int best = -1;
  for (std::uint32_t c = first_[k]; c < first_[k + 1]; ++c) {
    const double d = segmentDistance2(p, segments_[candidates_[c]]);
    if (d < least) least = d, best = static_cast<int>(candidates_[c]);
  }
  return best;
}

std::size_t DistanceField::bytes() const {
  std::size_t n = segments_.size() * sizeof(Segment2) + (first_.size() + candidates_.size()) * sizeof(std::uint32_t) + codes_.size();
  for (const auto& l : levels_) n += l.size();
  return n;
}

}  // namespace bimloc::sim::oracle
