#include "sim/odometry/barometer.hpp"

#include <cmath>

namespace bimloc::sim {

Barometer::Barometer(const BarometerConfig& config, std::uint64_t seed) : config_(config), rng_(seed ^ 0xBA20A1717Eull) {
  std::normal_distribution<double> n(0.0, 1.0);
  offset_m_ = config_.offset_sigma_m * n(rng_);
  drift_mps_ = config_.drift_sigma_mps * n(rng_);
}

double Barometer::read(double t_s, double true_altitude_m) {
  std::normal_distribution<double> n(0.0, 1.0);
  return true_altitude_m + offset_m_ + drift_mps_ * t_s + config_.noise_sigma_m * n(rng_);
}

double Barometer::sigma_m() const {
  return std::sqrt(config_.noise_sigma_m * config_.noise_sigma_m + config_.offset_sigma_m * config_.offset_sigma_m);
}

}  // namespace bimloc::sim
