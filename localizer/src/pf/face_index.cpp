#include "face_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::pf::detail {

FaceIndex::FaceIndex(std::vector<Landmark> faces, double cell_m) : FaceIndex(std::move(faces), cell_m, std::vector<bool>()) {}

FaceIndex::FaceIndex(std::vector<Landmark> faces, double cell_m, const std::vector<bool>& keep)
    : faces_(std::move(faces)), cell_m_(cell_m), per_cell_(cell_m) {
  if (faces_.empty()) return;
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& f : faces_) {
    const Eigen::Vector2d end = f.start + f.length_m * f.direction;
    lo = lo.cwiseMin(f.start).cwiseMin(end), hi = hi.cwiseMax(f.start).cwiseMax(end);
  }
  origin_ = lo - Eigen::Vector2d(cell_m_, cell_m_);
  nx_ = static_cast<int>(std::ceil((hi.x() - origin_.x()) / cell_m_)) + 2;
  ny_ = static_cast<int>(std::ceil((hi.y() - origin_.y()) / cell_m_)) + 2;
  std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
  seen_.assign(faces_.size(), 0u);
  // A face goes into every cell its segment comes within half a cell diagonal of (a superset
  // of the cells it crosses): then "cell centre within r + half diagonal" never misses it.
  const double reach = 0.7072 * cell_m_;
  for (std::uint32_t i = 0; i < faces_.size(); ++i) {
    if (!keep.empty() && !keep[i]) continue;
    const auto& f = faces_[i];
    const Eigen::Vector2d end = f.start + f.length_m * f.direction;
    const Eigen::Vector2d a = f.start.cwiseMin(end), b = f.start.cwiseMax(end);
    const int x0 = std::max(0, cellX(a.x() - reach)), x1 = std::min(nx_ - 1, cellX(b.x() + reach));
    const int y0 = std::max(0, cellY(a.y() - reach)), y1 = std::min(ny_ - 1, cellY(b.y() + reach));
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) {
        const Eigen::Vector2d c(origin_.x() + (ix + 0.5) * cell_m_, origin_.y() + (iy + 0.5) * cell_m_);
        const double u = std::clamp((c - f.start).dot(f.direction), 0.0, f.length_m);
        if ((f.start + u * f.direction - c).norm() <= reach) cells[static_cast<std::size_t>(iy * nx_ + ix)].push_back(i);
      }
  }
  starts_.reserve(cells.size() + 1);
  for (const auto& cell : cells) {
    starts_.push_back(static_cast<std::uint32_t>(members_.size()));
    members_.insert(members_.end(), cell.begin(), cell.end());
  }
  starts_.push_back(static_cast<std::uint32_t>(members_.size()));
}

MatchReach::MatchReach(double sigma_d_m, double sigma_angle_rad, double gate_mahalanobis2, double along_margin_m, double behind_m)
    : margin_m(along_margin_m) {
  const double k = std::sqrt(gate_mahalanobis2);
  // Within the gate, |d_az| + |d_el| <= sqrt(2 gate) sigma (Cauchy-Schwarz), and the angle
  // between the two normals is at most that sum.
  const double angle = std::sqrt(2.0) * k * sigma_angle_rad;
  infinite = angle >= M_PI;
  // The centroid of a least-squares plane's points lies on it; the trimmed refit may move the
  // plane a little off the centroid of the points it kept: 0.1 m of slack (in at()).
  across_m = k * sigma_d_m + std::max(0.0, behind_m), chord = 2.0 * std::sin(0.5 * angle);
}

double matchRadius(double range_m, double sigma_d_m, double sigma_angle_rad, double gate_mahalanobis2, double margin_m,
                   double behind_m) {
  return MatchReach(sigma_d_m, sigma_angle_rad, gate_mahalanobis2, margin_m, behind_m).at(range_m);
}

}  // namespace bimloc::pf::detail
