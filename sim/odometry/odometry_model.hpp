// Noisy odometry from the true motion: each planar increment (rot1, trans, rot2) gets the
// AMCL-style Gaussian noise, then the wandering scale and heading biases; height, roll and
// pitch come through as a legged robot's IMU and kinematics give them. The odom frame is the
// base's true pose at the first sample, on the floor (REP 105: odom starts where the robot does).
#pragma once

#include "sim/odometry/odometry_config.hpp"
#include "sim/odometry/odometry_sample.hpp"

#include <cstdint>
#include <optional>
#include <random>

namespace bimloc::sim {

class NoisyOdometry {
 public:
  // The odom frame is the base's start pose dropped to the floor it stands on, at map height
  // `floor_z` (REP 105: odom starts where the robot does; a robot knows its height above its
  // own floor, not the storey's elevation in the plan).
  NoisyOdometry(const OdometryConfig& config, std::uint64_t seed, double floor_z = 0.0);

  // The reading at time t for the true pose T_map_base (call with increasing t).
  OdometrySample step(double t_s, const Eigen::Isometry3d& T_map_base);

  // True map -> odom: where the odom frame is in the plan (for evaluation only).
  const Eigen::Isometry3d& T_map_odom_true() const { return T_map_odom_; }

 private:
  OdometryConfig config_;
  std::mt19937_64 rng_;
  Eigen::Isometry3d T_map_odom_ = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Vector3d> last_true_;  // x, y, yaw of the previous call
  Eigen::Vector3d estimate_ = Eigen::Vector3d::Zero();  // x, y, yaw in odom
  double last_t_ = 0.0;
  double floor_z_ = 0.0;
  double scale_bias_ = 0.0;
  double yaw_bias_ = 0.0;
  std::optional<OdometrySample> last_sample_;
};

}  // namespace bimloc::sim
