// The odometry error model: AMCL-style Gaussian noise on each increment (rot1, trans, rot2;
// Probabilistic Robotics p.136) plus a slowly wandering bias, so that error grows with distance.
#pragma once

#include <string>

namespace bimloc::sim {

struct OdometryConfig {
  std::string preset = "legged";  // legged | lidar | perfect | custom
  double rate_hz = 50.0;
  // Increment noise: variance of rot from a1*rot^2 + a2*trans^2, of trans from a3*trans^2 + a4*rot^2.
  double alpha1 = 0.0, alpha2 = 0.0, alpha3 = 0.0, alpha4 = 0.0;
  // Slowly wandering biases: a scale error on translation (fraction) and a heading drift per
  // metre, each drawn at the start with the given sigma and then wandering as a random walk of
  // the given strength per sqrt(metre travelled).
  double scale_bias_sigma = 0.0;
  double scale_bias_walk_per_sqrt_m = 0.0;
  double yaw_bias_sigma_rad_per_m = 0.0;
  double yaw_bias_walk_rad_per_m_per_sqrt_m = 0.0;
  // On a flight (issue 31): the height the legs report is off by a scale error of the height
  // climbed (drawn once per run with this sigma), and the feet slip: every increment's
  // translation and heading noise is this many times its flat-ground sigma (1: none extra).
  double stair_height_scale_sigma = 0.0;
  double stair_slip_factor = 1.0;
};

// legged: about 1-2 % of distance; lidar: about 0.5 %; perfect: none. Throws
// std::invalid_argument naming the presets for an unknown name.
OdometryConfig odometryPreset(const std::string& name);

}  // namespace bimloc::sim
