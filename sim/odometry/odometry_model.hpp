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

  // The reading at time t for the true pose T_map_base (call with increasing t); on_stairs:
  // the base is on a flight (the increment since the last call counts as climbed, with the
  // stair model of OdometryConfig). Off the stairs, the same readings as before the stairs
  // existed: the stair draws have their own random stream.
  OdometrySample step(double t_s, const Eigen::Isometry3d& T_map_base, bool on_stairs = false);
  // The height error accumulated on flights so far (odometry z minus true z), for tests.
  double heightError_m() const { return height_error_m_; }

  // True map -> odom: where the odom frame is in the plan (for evaluation only).
  const Eigen::Isometry3d& T_map_odom_true() const { return T_map_odom_; }

 private:
  OdometryConfig config_;
  std::mt19937_64 rng_;
  std::mt19937_64 stair_rng_;  // the stair model's draws
  double stair_height_scale_ = 0.0;
  double height_error_m_ = 0.0;
  std::optional<double> last_true_z_;
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
