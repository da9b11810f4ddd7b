// AMCL's observation: the 3D lidar turn as the 2D laser scan ROS amcl expects
// (pointcloud_to_laserscan: the points in a height band, the nearest per bearing), then the
// max_beams beams amcl's likelihood field model reads of it.
#pragma once

#include <bimloc/peers/amcl_config.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace bimloc::peers::amcl {

// A laser scan in the levelled base frame: ranges[i] at bearing angle_min + i * increment
// (+inf: no return in that beam).
struct LaserScan {
  double angle_min = -M_PI;
  double increment = M_PI / 180.0;
  std::vector<double> ranges;
  std::vector<Eigen::Vector2d> ends;  // the nearest point of each beam (x, y), where it has one
  int points = 0;      // points given
  int non_finite = 0;  // NaN or inf points, dropped
  int in_band = 0;     // points in the height band and the range limits, kept
};

// The points (lidar frame) through the mount into the base frame, levelled by the odometry's
// roll and pitch (the IMU's), kept when their height above the floor (the odometry's z is the
// base's: REP 105, odom on the floor where the robot started) is in [band_min_m, band_max_m]
// and their horizontal range in [laser_min_range_m, laser_max_range_m].
LaserScan projectScan(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_base_lidar,
                      const Eigen::Isometry3d& T_odom_base, const AmclConfig& config);

// The beams ROS amcl's likelihood field model reads (amcl_laser.cpp): every step-th with
// step = (count - 1) / (max_beams - 1), integer division, at least 1; beams without a return
// (max range) skipped. Their end points in the base frame (the returns' own bearings, not the
// bins' centres: the 3D lidar measured them).
std::vector<Eigen::Vector2d> selectBeams(const LaserScan& scan, int max_beams);

}  // namespace bimloc::peers::amcl
