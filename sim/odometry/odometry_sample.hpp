// One odometry reading: the base's pose in the odom frame (REP 105: odom -> base_link).
#pragma once

#include <Eigen/Geometry>

namespace bimloc::sim {

struct OdometrySample {
  double stamp_s = 0.0;
  Eigen::Isometry3d T_odom_base = Eigen::Isometry3d::Identity();
  Eigen::Vector3d linear_velocity_base = Eigen::Vector3d::Zero();   // m/s, in base_link
  Eigen::Vector3d angular_velocity_base = Eigen::Vector3d::Zero();  // rad/s, in base_link
};

struct GroundTruthSample {
  double stamp_s = 0.0;
  Eigen::Isometry3d T_map_base = Eigen::Isometry3d::Identity();
  // The storey the base is on (index into the building's storeys; while on a flight, the one
  // it came from) and whether it is on a flight (issue 31). Not in recordings' ground truth.
  std::size_t storey = 0;
  bool on_stairs = false;
};

}  // namespace bimloc::sim
