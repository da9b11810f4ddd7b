#include "sim/oracle/wall_field.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim::oracle {
float segmentDistance(const Eigen::Vector2d& p, const Segment2& s) {
  const Eigen::Vector2d ab = s.b - s.a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - s.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return static_cast<float>((s.a + t * ab - p).norm());
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
    : cell_(static_cast<float>(cell_m)), clamp_(static_cast<float>(clamp_m)) {
  lower_ = Eigen::Vector2d::Constant(walls.empty() ? 0.0 : 1e300), upper_ = Eigen::Vector2d::Constant(walls.empty() ? 0.0 : -1e300);
  for (const auto& s : walls) lower_ = lower_.cwiseMin(s.a).cwiseMin(s.b), upper_ = upper_.cwiseMax(s.a).cwiseMax(s.b);
  lower_.array() -= margin_m, upper_.array() += margin_m;
  nx_ = static_cast<int>(std::ceil((upper_.x() - lower_.x()) / cell_m)) + 1;
  ny_ = static_cast<int>(std::ceil((upper_.y() - lower_.y()) / cell_m)) + 1;
  values_.assign(static_cast<std::size_t>(nx_) * ny_, clamp_);
  // Exact distances, each segment writing the cells within clamp of it.
  for (const auto& s : walls)
    forCellsNear(s, lower_, cell_m, clamp_m, nx_, ny_, [&](std::size_t at, float d) { values_[at] = std::min(values_[at], d); });
  // The min-pyramid, quantized downwards (still a lower bound).
  inv_cell_ = 1.0f / cell_;
  levels_.resize(kLevels);
  const float scale = 255.0f / clamp_;
  codes_.resize(values_.size());
  for (std::size_t k = 0; k < values_.size(); ++k) codes_[k] = static_cast<std::uint8_t>(std::min(255.0f, std::floor(values_[k] * scale)));
  for (int k = 1; k <= kLevels; ++k) {
    auto& level = levels_[k - 1];
    level.assign(values_.size(), 0);
    const int half = 1 << (k - 1);
    for (int j = 0; j + 2 * half <= ny_; ++j)
      for (int i = 0; i + 2 * half <= nx_; ++i) {
        const std::size_t at = static_cast<std::size_t>(j) * nx_ + i;
        if (k == 1) {
          const float m = std::min(std::min(cell(i, j), cell(i + 1, j)), std::min(cell(i, j + 1), cell(i + 1, j + 1)));
          level[at] = static_cast<std::uint8_t>(std::min(255.0f, std::floor(m * scale)));
        } else {
          const auto& below = levels_[k - 2];
          const std::size_t dx = half, dy = static_cast<std::size_t>(half) * nx_;
          level[at] = std::min(std::min(below[at], below[at + dx]), std::min(below[at + dy], below[at + dx + dy]));
        }
      }
  }
}

std::size_t DistanceField::bytes() const {
  std::size_t n = values_.size() * sizeof(float) + codes_.size();
  for (const auto& l : levels_) n += l.size();
  return n;
}

}  // namespace bimloc::sim::oracle
