#include "peers/amcl/amcl.hpp"

#include "peers/amcl/scan.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace bimloc::peers::amcl {
namespace {

void check(const AmclConfig& c) {
  std::ostringstream bad;
  if (c.min_particles < 1 || c.max_particles < c.min_particles) bad << "min_particles (" << c.min_particles << ") must be in [1, max_particles (" << c.max_particles << ")]; ";
  if (!(c.kld_err > 0) || !(c.kld_z > 0)) bad << "kld_err and kld_z must be positive; ";
  if (c.resample_interval < 1) bad << "resample_interval must be at least 1; ";
  if (c.max_beams < 1) bad << "max_beams must be at least 1; ";
  if (!(c.sigma_hit_m > 0) || !(c.likelihood_max_dist_m > 0)) bad << "sigma_hit_m and likelihood_max_dist_m must be positive; ";
  if (!(c.laser_max_range_m > c.laser_min_range_m)) bad << "laser_max_range_m must exceed laser_min_range_m; ";
  if (!(c.band_max_m > c.band_min_m)) bad << "band_max_m (" << c.band_max_m << ") must exceed band_min_m (" << c.band_min_m << "); ";
  if (!(c.map_resolution_m > 0)) bad << "map_resolution_m must be positive; ";
  if (!(c.scan_angle_increment_deg > 0)) bad << "scan_angle_increment_deg must be positive; ";
  if (!(c.lost_xy_std_m >= c.converged_xy_std_m) || !(c.lost_yaw_std_deg >= c.converged_yaw_std_deg))
    bad << "lost_*_std must be at least converged_*_std; ";
  const std::string b = bad.str();
  if (!b.empty()) throw std::invalid_argument("amcl: " + b.substr(0, b.size() - 2));
}

double xyStd(const Eigen::Matrix3d& covariance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(covariance.topLeftCorner<2, 2>().eval());
  return std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff()));
}

}  // namespace

Amcl::Amcl(const bim::Storey& storey, const Eigen::Isometry3d& T_base_lidar, const AmclConfig& config, std::uint64_t seed)
    : config_(config), T_base_lidar_(T_base_lidar), storey_name_(storey.name), elevation_m_(storey.elevation_m), rng_(seed) {
  check(config_);
  slice_ = sliceStorey(storey, config_);
  field_ = std::make_unique<LikelihoodField>(slice_.grid, config_.likelihood_max_dist_m);
  model_ = std::make_unique<BeamModel>(*field_, config_);
  free_ = amcl::freeSpace(*field_, storey, config_.free_clearance_m);
  pending_warnings_ = slice_.warnings;
  for (const auto& w : free_.warnings) pending_warnings_.push_back(w);
  no_obstacles_ = slice_.grid.occupiedCount() == 0;
  if (no_obstacles_) {
    std::ostringstream w;
    w << "amcl: the slice of storey '" << storey.name << "' between " << config_.band_min_m << " and " << config_.band_max_m
      << " m above its floor has no obstacle: nothing to localize against, AMCL will not converge";
    pending_warnings_.push_back(w.str());
  }
  // ROS pf_init (initial pose, Gaussian) or pf_init_model (global_localization: uniform over
  // the free space); max_particles either way.
  particles_.resize(static_cast<std::size_t>(config_.max_particles));
  std::normal_distribution<double> n(0.0, 1.0);
  const double yaw0 = config_.initial_pose_yaw_deg * M_PI / 180.0, sigma_yaw = config_.initial_sigma_yaw_deg * M_PI / 180.0;
  for (Particle& p : particles_) {
    if (config_.use_initial_pose) {
      const double x = config_.initial_pose_x_m + config_.initial_sigma_xy_m * n(rng_);
      const double y = config_.initial_pose_y_m + config_.initial_sigma_xy_m * n(rng_);
      p.pose = {x, y, wrapAngle(yaw0 + sigma_yaw * n(rng_))};
    } else {
      p.pose = randomFreePose(rng_);
    }
    p.weight = 1.0 / static_cast<double>(particles_.size());
  }
  stats_ = clusterStats(particles_);
}

PlanarPose Amcl::randomFreePose(std::mt19937_64& rng) const {
  // ROS uniformPoseGenerator (NEW_UNIFORM_SAMPLING): a free cell's centre, any heading.
  std::uniform_int_distribution<std::size_t> cell(0, free_.cells.size() - 1);
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI);
  const std::uint32_t c = free_.cells[cell(rng)];
  const Grid& g = slice_.grid;
  const Eigen::Vector2d xy = g.centre(static_cast<int>(c % g.width), static_cast<int>(c / g.width));
  return {xy.x(), xy.y(), yaw(rng)};
}

bool Amcl::gatePasses(const PlanarPose& odom) const {
  if (!initialized_) return true;  // ROS: the first scan initializes and is used
  // ROS amcl_node: fabs(dx) > update_min_d || fabs(dy) > update_min_d || fabs(dyaw) > update_min_a.
  return std::abs(odom.x() - odom_.x()) > config_.update_min_d_m || std::abs(odom.y() - odom_.y()) > config_.update_min_d_m ||
         std::abs(wrapAngle(odom.z() - odom_.z())) > config_.update_min_a_rad;
}

bool Amcl::wantsPoints(const Eigen::Isometry3d& T_odom_base) const { return gatePasses(planarPose(T_odom_base)); }

Eigen::Isometry3d Amcl::poseOf(const PlanarPose& p, const Eigen::Isometry3d& T_odom_base) const {
  // The plan's pose in 3D as the paper's filter gives it: the base's height above the floor
  // and its tilt from the odometry, on the storey's floor.
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(p.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix() * tiltOf(T_odom_base.linear());
  T.translation() = Eigen::Vector3d(p.x(), p.y(), elevation_m_ + T_odom_base.translation().z());
  return T;
}

void Amcl::weigh(const std::vector<Eigen::Vector2d>& beams) {
  // ROS pf_update_sensor: weights times the beam model, normalised; the running averages of
  // the likelihood for augmented MCL (Probabilistic Robotics p. 258).
  const double total = model_->weigh(particles_, beams);
  if (!(total > 0) || !std::isfinite(total)) {
    for (Particle& p : particles_) p.weight = 1.0 / static_cast<double>(particles_.size());
    return;
  }
  const double w_avg = total / static_cast<double>(particles_.size());
  for (Particle& p : particles_) p.weight /= total;
  if (!config_.recovery) return;
  w_slow_ = w_slow_ == 0.0 ? w_avg : w_slow_ + config_.recovery_alpha_slow * (w_avg - w_slow_);
  w_fast_ = w_fast_ == 0.0 ? w_avg : w_fast_ + config_.recovery_alpha_fast * (w_avg - w_fast_);
}

void Amcl::publish(const PlanarPose& odom) {
  stats_ = clusterStats(particles_);
  map_odom_ = compose(stats_.best.mean, inverse(odom));
  published_ = true;
  // Convergence by the whole set's spread, with hysteresis (AmclConfig).
  const double xy = xyStd(stats_.set.covariance), yaw = std::sqrt(std::max(0.0, stats_.set.covariance(2, 2)));
  const double deg = M_PI / 180.0;
  if (!converged_)
    converged_ = !no_obstacles_ && weighed_updates_ > 0 && xy <= config_.converged_xy_std_m && yaw <= config_.converged_yaw_std_deg * deg;
  else
    converged_ = xy <= config_.lost_xy_std_m && yaw <= config_.lost_yaw_std_deg * deg;
  ever_converged_ = ever_converged_ || converged_;
}

void Amcl::update(double stamp_s, const PlanarPose& odom, const Eigen::Isometry3d& T_odom_base, const std::vector<Eigen::Vector3f>& points,
                  PeerStep& s) {
  s.report.updated = true;  // the gates passed: the particles move, and are weighed if the scan has beams
  if (!initialized_) {
    initialized_ = true;  // ROS: the first scan sets pf_odom_pose_ and is weighed, no motion
    resample_count_ = 0;
  } else {
    const PlanarPose delta(odom.x() - odom_.x(), odom.y() - odom_.y(), wrapAngle(odom.z() - odom_.z()));
    sampleMotion(particles_, odom_, delta, config_, rng_);
  }
  odom_ = odom;
  const LaserScan scan = projectScan(points, T_base_lidar_, T_odom_base, config_);
  if (scan.non_finite > 0 && !warned_non_finite_) {
    warned_non_finite_ = true;
    s.warnings.push_back("amcl: dropped " + std::to_string(scan.non_finite) + " non-finite (NaN or inf) points of " +
                         std::to_string(scan.points) + " at t=" + std::to_string(stamp_s) + " s (warned once; later ones are dropped too)");
  }
  const std::vector<Eigen::Vector2d> beams = selectBeams(scan, config_.max_beams);
  if (beams.empty()) {
    // No observation: the particles moved, nothing weighs them, nothing to resample on.
    if (!warned_empty_) {
      warned_empty_ = true;
      std::ostringstream w;
      w << "amcl: no lidar return between " << config_.band_min_m << " and " << config_.band_max_m << " m above the floor within "
        << config_.laser_min_range_m << "-" << config_.laser_max_range_m << " m at t=" << stamp_s
        << " s: the update moved the particles and weighed none (warned once)";
      s.warnings.push_back(w.str());
    }
    publish(odom);
    return;
  }
  weigh(beams);
  ++weighed_updates_;
  if (++resample_count_ % config_.resample_interval == 0) {
    double w_diff = 0;
    if (config_.recovery && w_slow_ > 0) w_diff = std::max(0.0, 1.0 - w_fast_ / w_slow_);
    particles_ = resampleKld(particles_, config_, w_diff, [this](std::mt19937_64& rng) { return randomFreePose(rng); }, rng_);
    if (w_diff > 0) w_slow_ = w_fast_ = 0;  // ROS: "to avoid spiraling off into complete randomness"
    publish(odom);
  }
}

PeerStep Amcl::step(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<Eigen::Vector3f>* points_lidar) {
  PeerStep s;
  s.report.method = "amcl";
  s.warnings = std::move(pending_warnings_);
  pending_warnings_.clear();
  if (!T_odom_base.matrix().allFinite()) {
    // No odometry this turn: nothing moves the particles; the last pose stands.
    if (!warned_odometry_) s.warnings.push_back("amcl: non-finite odometry pose at t=" + std::to_string(stamp_s) + " s: step skipped (warned once)");
    warned_odometry_ = true;
  } else {
    last_T_odom_base_ = T_odom_base;
    const PlanarPose odom = planarPose(T_odom_base);
    if (points_lidar && gatePasses(odom)) update(stamp_s, odom, T_odom_base, *points_lidar, s);
    // Between updates the odometry carries the last published pose (ROS: map -> odom).
    if (!published_) map_odom_ = compose(stats_.best.mean, inverse(odom));
  }
  s.T_map_base = poseOf(compose(map_odom_, planarPose(last_T_odom_base_)), last_T_odom_base_);
  s.covariance = stats_.set.covariance;
  s.report.converged = converged_;
  s.report.relocalizing = ever_converged_ && !converged_;
  s.report.particles = static_cast<int>(particles_.size());
  s.report.score = xyStd(stats_.set.covariance);
  s.report.poses.reserve(particles_.size());
  for (const Particle& p : particles_) s.report.poses.push_back(p.pose);
  return s;
}

}  // namespace bimloc::peers::amcl

namespace bimloc::peers {
std::unique_ptr<PeerLocalizer> makeAmcl(const bim::Storey& storey, const Eigen::Isometry3d& T_base_lidar, const AmclConfig& config,
                                        std::uint64_t seed) {
  return std::make_unique<amcl::Amcl>(storey, T_base_lidar, config, seed);
}
}  // namespace bimloc::peers
