// AMCL (ROS navigation's amcl; Probabilistic Robotics ch. 8) as the paper's first baseline.
// Defaults are the ROS amcl node's (../shared/reference.md, "Baselines"); the fields that ROS
// does not have (the map is sliced from the plan, the scan from a 3D lidar, and a convergence
// criterion for the bench) say where their values come from.
#pragma once

namespace bimloc::peers {

struct AmclConfig {
  // --- The particle filter (ROS amcl "Overall filter parameters").
  int min_particles = 100;   // ROS amcl ~min_particles
  int max_particles = 5000;  // ROS amcl ~max_particles
  double kld_err = 0.01;     // ROS amcl ~kld_err
  // ROS amcl ~kld_z: used as the upper standard normal quantile itself (ROS's pf.c puts it in
  // Fox's bound as z_{1-delta}), not as a probability.
  double kld_z = 0.99;
  double update_min_d_m = 0.2;          // ROS amcl ~update_min_d (|dx| or |dy| in the odom frame)
  double update_min_a_rad = 0.5235988;  // ROS amcl ~update_min_a (pi/6)
  int resample_interval = 2;            // ROS amcl ~resample_interval
  // Augmented MCL (Probabilistic Robotics, table 8.3): random particles when the short-term
  // likelihood average falls below the long-term one. Off by default, as in ROS (whose
  // alphas default to 0); `recovery: true` turns it on with ROS's suggested rates.
  bool recovery = false;
  double recovery_alpha_slow = 0.001;  // ROS amcl ~recovery_alpha_slow (0.001 suggested)
  double recovery_alpha_fast = 0.1;    // ROS amcl ~recovery_alpha_fast (0.1 suggested)

  // --- The laser model (ROS amcl ~laser_model_type likelihood_field).
  double z_hit = 0.95;                 // ROS amcl ~laser_z_hit
  double z_rand = 0.05;                // ROS amcl ~laser_z_rand
  double sigma_hit_m = 0.2;            // ROS amcl ~laser_sigma_hit
  double likelihood_max_dist_m = 2.0;  // ROS amcl ~laser_likelihood_max_dist
  int max_beams = 30;                  // ROS amcl ~laser_max_beams
  // ROS amcl ~laser_min_range / ~laser_max_range (-1 there: the scan's own). Shorter returns
  // are the base's own legs; 100 m is the VLP-16's range (its z_rand density is 1/max).
  double laser_min_range_m = 0.5;
  double laser_max_range_m = 100.0;

  // --- The odometry model (ROS amcl ~odom_model_type diff; Probabilistic Robotics table 5.6).
  double odom_alpha1 = 0.2;  // ROS amcl ~odom_alpha1: rotation noise from rotation
  double odom_alpha2 = 0.2;  // ROS amcl ~odom_alpha2: rotation noise from translation
  double odom_alpha3 = 0.2;  // ROS amcl ~odom_alpha3: translation noise from translation
  double odom_alpha4 = 0.2;  // ROS amcl ~odom_alpha4: translation noise from rotation

  // --- The 2D world: the map and the scan are the same height band above the floor.
  // A slice above the floor (with its clutter and skirting, and whatever the legs' tilt shows
  // of the floor) and below door heads (2.0-2.1 m, so doorways stay open in the map).
  double band_min_m = 0.3;
  double band_max_m = 1.8;
  double map_resolution_m = 0.05;  // ROS map_server / gmapping ~delta default
  // Door leaves (IfcDoor) in the map: off, a building under construction has doorways before
  // it has doors (the simulator leaves them out too; bim::ExtractOptions::door_leaves).
  bool map_doors = false;
  // Where global localization puts particles: free cells inside the building (inside a
  // room's footprint, or enclosed by the slice), at least this far from any obstacle (the
  // base's half width; also keeps particles out of the gap between a wall's two faces).
  double free_clearance_m = 0.25;
  // pointcloud_to_laserscan ~angle_increment (1 deg): the 3D points become a 360-beam scan,
  // the nearest return per beam, before max_beams of them are taken as ROS amcl does.
  double scan_angle_increment_deg = 1.0;

  // --- Global localization, or a known start (ROS amcl ~initial_pose_* and ~initial_cov_*).
  bool use_initial_pose = false;    // false: particles uniform over the free space
  double initial_pose_x_m = 0.0;    // ROS amcl ~initial_pose_x
  double initial_pose_y_m = 0.0;    // ROS amcl ~initial_pose_y
  double initial_pose_yaw_deg = 0;  // ROS amcl ~initial_pose_a
  double initial_sigma_xy_m = 0.5;  // ROS amcl ~initial_cov_xx = ~initial_cov_yy = 0.5^2
  double initial_sigma_yaw_deg = 15;  // ROS amcl ~initial_cov_aa = (pi/12)^2

  // --- Convergence (not ROS's: amcl publishes a pose whatever its spread). Declared when the
  // particles' spread (the whole set's covariance, which ROS publishes) is small enough that
  // the estimate is within the bench's false-convergence tolerance (0.5 m, 10 deg) at two
  // standard deviations; given up when one standard deviation reaches it.
  double converged_xy_std_m = 0.25;    // largest sqrt(eigenvalue) of the xy covariance
  double converged_yaw_std_deg = 5.0;  // sqrt of the circular yaw variance
  double lost_xy_std_m = 0.5;
  double lost_yaw_std_deg = 10.0;
};

}  // namespace bimloc::peers
