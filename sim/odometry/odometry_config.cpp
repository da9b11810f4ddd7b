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
    // Stairs. Height: proprioceptive odometry of quadrupeds closing vertical loops over stairs
    // returned 0.219 m after about 15 m of height (Astrall robot A: 1.5 %), 0.540 m after about
    // 20 m (wheel-legged robot C: 2.7 %) and under 0.1 m after about 8 m (Unitree Go2:
    // < 1.25 %) ("Contact-Anchored Proprioceptive Odometry for Quadruped Robots", arXiv
    // 2602.17393, 2026, abstract): 1.5 % of the height climbed, one sigma.
    c.stair_height_scale_sigma = 0.015;
    // Slip: in the same paper robot A's error per metre was 18 times worse on its vertical loop
    // (0.219 m / 15 m of height) than on its horizontal one (0.164 m / 200 m), the Go2's no
    // worse (< 0.1 m / 8 m against 2.2 m / 120 m); COCLO (Contact-Centric Leg Odometry,
    // arXiv 1911.05176) also finds stairs the hardest of flat, ramp and stairs. A factor of 3
    // on the increment noise is our choice between those two figures, not a measured value.
    c.stair_slip_factor = 3.0;
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
