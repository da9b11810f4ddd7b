// AMCL (ROS navigation's amcl; Probabilistic Robotics ch. 8) as the paper's first baseline.
// Defaults are the ROS amcl node's (../shared/reference.md, "Baselines").
#pragma once

namespace bimloc::peers {

struct AmclConfig {
  int min_particles = 100;   // ROS amcl ~min_particles
  int max_particles = 5000;  // ROS amcl ~max_particles
  double kld_err = 0.01;     // ROS amcl ~kld_err
  double kld_z = 0.99;       // ROS amcl ~kld_z
  double update_min_d_m = 0.2;         // ROS amcl ~update_min_d
  double update_min_a_rad = 0.5235988; // ROS amcl ~update_min_a (pi/6)
  int resample_interval = 2;           // ROS amcl ~resample_interval
  double z_hit = 0.95;                 // ROS amcl ~laser_z_hit
  double z_rand = 0.05;                // ROS amcl ~laser_z_rand
  double sigma_hit_m = 0.2;            // ROS amcl ~laser_sigma_hit
  double likelihood_max_dist_m = 2.0;  // ROS amcl ~laser_likelihood_max_dist
  int max_beams = 30;                  // ROS amcl ~laser_max_beams
  double recovery_alpha_slow = 0.0;    // ROS amcl ~recovery_alpha_slow (off; 0.001 suggested)
  double recovery_alpha_fast = 0.0;    // ROS amcl ~recovery_alpha_fast (off; 0.1 suggested)
};

}  // namespace bimloc::peers
