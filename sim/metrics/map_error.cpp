#include "sim/metrics/map_error.hpp"

#include <cmath>

namespace bimloc::sim {

void MapError::add(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_map_lidar) {
  for (std::size_t i = 0; i < points_lidar.size(); i += static_cast<std::size_t>(stride_)) {
    const Eigen::Vector3d p = points_lidar[i].cast<double>();
    if (!p.allFinite()) continue;
    const double d = mesh_.distance(T_map_lidar * p);
    if (!std::isfinite(d)) continue;
    sum_sq_ += d * d;
    ++n_;
  }
}

void MapErrorSampler::step(const LocalizationResult& r, const Eigen::Isometry3d& T_base_lidar,
                           const std::function<std::vector<Eigen::Vector3f>()>& points_lidar) {
  ++steps_;
  const bool placed = r.storey && (r.state == LocalizationState::Converged || r.state == LocalizationState::Tracking);
  if (!placed || steps_ % every_ != 0) return;
  if (!error_) error_.emplace(building_.storeys.at(*r.storey));
  error_->add(points_lidar(), r.T_map_base * T_base_lidar);
}

std::optional<double> MapErrorSampler::rmse_m() const {
  if (!error_ || error_->points() == 0) return std::nullopt;
  return error_->rmse_m();
}

double MapError::rmse_m() const { return n_ == 0 ? NAN : std::sqrt(sum_sq_ / static_cast<double>(n_)); }

}  // namespace bimloc::sim
