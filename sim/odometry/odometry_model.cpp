#include "sim/odometry/odometry_model.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <cmath>

namespace bimloc::sim {
namespace {

double wrap(double a) { return bimloc::wrapAngle(a); }

Eigen::Vector3d planar(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d x = T.linear().col(0);
  return {T.translation().x(), T.translation().y(), std::atan2(x.y(), x.x())};
}

Eigen::Isometry3d fromPlanar(const Eigen::Vector3d& p, double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(p.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.x(), p.y(), z);
  return T;
}

}  // namespace

NoisyOdometry::NoisyOdometry(const OdometryConfig& config, std::uint64_t seed, double floor_z)
    : config_(config), rng_(seed), stair_rng_(seed ^ 0x57A125C11B5ull), floor_z_(floor_z) {
  std::normal_distribution<double> n(0.0, 1.0);
  scale_bias_ = config_.scale_bias_sigma * n(rng_);
  yaw_bias_ = config_.yaw_bias_sigma_rad_per_m * n(rng_);
  std::normal_distribution<double> stair(0.0, 1.0);
  stair_height_scale_ = config_.stair_height_scale_sigma * stair(stair_rng_);
}

OdometrySample NoisyOdometry::step(double t_s, const Eigen::Isometry3d& T_map_base, bool on_stairs) {
  const Eigen::Vector3d now = planar(T_map_base);
  if (!last_true_) {
    // The odom frame: the base's start pose, dropped to the floor it stands on.
    T_map_odom_ = fromPlanar(now, floor_z_);
    last_true_ = now;
    last_t_ = t_s;
  }
  // Probabilistic Robotics, sample_motion_model_odometry (p.136), with the ROS AMCL alphas.
  const Eigen::Vector3d prev = *last_true_;
  const Eigen::Vector2d delta = now.head<2>() - prev.head<2>();
  const double trans = delta.norm();
  const double rot1 = trans < 1e-6 ? 0.0 : wrap(std::atan2(delta.y(), delta.x()) - prev.z());
  const double rot2 = wrap(now.z() - prev.z() - rot1);
  std::normal_distribution<double> n(0.0, 1.0);
  const auto& c = config_;
  const double r1 = rot1 - std::sqrt(c.alpha1 * rot1 * rot1 + c.alpha2 * trans * trans) * n(rng_);
  double tr = trans - std::sqrt(c.alpha3 * trans * trans + c.alpha4 * (rot1 * rot1 + rot2 * rot2)) * n(rng_);
  double r2 = rot2 - std::sqrt(c.alpha1 * rot2 * rot2 + c.alpha2 * trans * trans) * n(rng_);
  // The biases: a scale error and a heading drift that grow the error with the distance walked.
  tr *= 1.0 + scale_bias_;
  r2 += yaw_bias_ * trans;
  if (on_stairs && c.stair_slip_factor > 1.0) {
    // Slip: the flat-ground noise again, scaled so the total sigma is the factor times it.
    // Its own distribution: libstdc++'s caches every second draw, which must stay rng_'s.
    std::normal_distribution<double> slip(0.0, 1.0);
    const double extra = std::sqrt(c.stair_slip_factor * c.stair_slip_factor - 1.0);
    tr -= extra * std::sqrt(c.alpha3 * trans * trans + c.alpha4 * (rot1 * rot1 + rot2 * rot2)) * slip(stair_rng_);
    r2 -= extra * std::sqrt(c.alpha1 * rot2 * rot2 + c.alpha2 * trans * trans) * slip(stair_rng_);
  }
  const double true_z = T_map_base.translation().z();
  if (on_stairs && last_true_z_) height_error_m_ += stair_height_scale_ * std::abs(true_z - *last_true_z_);
  last_true_z_ = true_z;
  scale_bias_ += c.scale_bias_walk_per_sqrt_m * std::sqrt(trans) * n(rng_);
  yaw_bias_ += c.yaw_bias_walk_rad_per_m_per_sqrt_m * std::sqrt(trans) * n(rng_);

  estimate_.x() += tr * std::cos(estimate_.z() + r1);
  estimate_.y() += tr * std::sin(estimate_.z() + r1);
  estimate_.z() = wrap(estimate_.z() + r1 + r2);
  last_true_ = now;

  // Height, roll and pitch: what the legs and the IMU measure, relative to the odom frame.
  const Eigen::Isometry3d T_odom_base_true = T_map_odom_.inverse() * T_map_base;
  const Eigen::Matrix3d R_true = T_odom_base_true.linear();
  const double true_yaw = yawOf(R_true);
  OdometrySample sample;
  sample.stamp_s = t_s;
  sample.T_odom_base = fromPlanar(estimate_, T_odom_base_true.translation().z() + height_error_m_);
  sample.T_odom_base.linear() =
      Eigen::AngleAxisd(estimate_.z() - true_yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R_true;
  if (last_sample_ && t_s > last_t_) {
    const double dt = t_s - last_t_;
    const Eigen::Isometry3d d = last_sample_->T_odom_base.inverse() * sample.T_odom_base;
    sample.linear_velocity_base = d.translation() / dt;
    const Eigen::AngleAxisd aa(d.linear());
    sample.angular_velocity_base = aa.axis() * aa.angle() / dt;
  }
  last_t_ = t_s;
  last_sample_ = sample;
  return sample;
}

}  // namespace bimloc::sim
