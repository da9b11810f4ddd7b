#include "sim/odometry/odometry_config.hpp"

#include <stdexcept>

namespace bimloc::sim {

OdometryConfig odometryPreset(const std::string& name) {
  OdometryConfig c;
  c.preset = name;
  if (name == "perfect") return c;
  if (name == "legged") {
    // Proprioceptive leg odometry of a quadruped: 0.1-2 % of distance reported (reference.md);
    // tuned so that `bimloc bench odometry` measures about 1.5 % on a 100 m walk.
    c.alpha1 = 0.01, c.alpha2 = 2e-4, c.alpha3 = 0.01, c.alpha4 = 0.002;
    c.scale_bias_sigma = 0.01, c.scale_bias_walk_per_sqrt_m = 0.001;
    c.yaw_bias_sigma_rad_per_m = 5e-4, c.yaw_bias_walk_rad_per_m_per_sqrt_m = 5e-5;
    return c;
  }
  if (name == "lidar") {
    // Lidar odometry (scan matching): about 0.5 % of distance.
    c.alpha1 = 0.002, c.alpha2 = 2e-5, c.alpha3 = 0.002, c.alpha4 = 5e-4;
    c.scale_bias_sigma = 0.003, c.scale_bias_walk_per_sqrt_m = 3e-4;
    c.yaw_bias_sigma_rad_per_m = 1.5e-4, c.yaw_bias_walk_rad_per_m_per_sqrt_m = 1.5e-5;
    return c;
  }
  throw std::invalid_argument("unknown odometry preset '" + name + "' (presets: legged, lidar, perfect)");
}

}  // namespace bimloc::sim
