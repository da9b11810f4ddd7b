// Velodyne VLP-16 model parameters (VLP-16 User Manual rev. A; numbers in ../shared/reference.md).
#pragma once

#include <Eigen/Geometry>

namespace bimloc::sim {

struct Vlp16Config {
  double rpm = 600.0;                // 300..1200 in steps of 60; 600 = 10 Hz, 0.2 deg azimuth step
  double min_range_m = 0.4;          // the ROS driver's VLP-16 default
  double max_range_m = 100.0;
  // Gaussian range noise. Default 0.008 m as Gazebo's velodyne_simulator: inside the manual's
  // +-3 cm accuracy (read as about 3 sigma of 1 cm), and what the paper's simulation had.
  double range_noise_sigma_m = 0.008;
  double dropout_probability = 0.0;  // each return independently lost
  bool motion_distortion = true;     // cast every firing from the sensor pose at its own instant
  bool use_packets = true;           // cast each firing's 16 rays as one Embree packet
  // The loop de-skews each turn with the base's noisy odometry before the localizer sees it,
  // as a robot's driver or LIO does (and `bimloc localize` with a per-point time field):
  // every point moved into the lidar frame at the mid-turn stamp (run_scenario.cpp).
  bool deskew = true;
  // Mount: T_base_lidar. Default on top of Spot's body, as on the paper's robot.
  Eigen::Isometry3d T_base_lidar = Eigen::Translation3d(0.0, 0.0, 0.25) * Eigen::Isometry3d::Identity();
};

}  // namespace bimloc::sim
