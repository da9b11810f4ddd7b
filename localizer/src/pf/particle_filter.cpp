// The filter's cycle reads like the paper: predict with odometry -> associate rooms and walls
// -> weight -> resample -> check convergence -> initial transformation map <- odom.
#include <bimloc/pf/particle_filter.hpp>

#include "filter_access.hpp"
#include "filter_impl.hpp"

#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/geometry/planar_pose.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace bimloc::pf {
namespace {

using detail::near;
using detail::tiltOf;
using detail::wrapAngle;

// Odometry jumps beyond these in one step are reported, and spread the particles accordingly.
constexpr double kJumpM = 1.0;
constexpr double kJumpRad = M_PI / 4;

}  // namespace

ParticleFilter::ParticleFilter(const bim::Storey& storey, const Eigen::Isometry3d& T_base_lidar,
                               const ParticleFilterConfig& config)
    : impl_(std::make_unique<Impl>(storey, T_base_lidar, config)) {}
ParticleFilter::~ParticleFilter() = default;
ParticleFilter::ParticleFilter(ParticleFilter&&) noexcept = default;

void ParticleFilter::predict(const Eigen::Isometry3d& T_odom_base) {
  auto& m = *impl_;
  if (!T_odom_base.matrix().allFinite()) return;  // a broken reading: keep the last one
  const Eigen::Isometry3d step = m.odom.inverse() * T_odom_base;
  const bool jump = m.last_odom && (step.translation().head<2>().norm() > kJumpM || std::abs(yawOf(step.linear())) > kJumpRad);
  if (jump) {
    // Reported with the next update; the increment's noise (proportional to it) spreads the
    // particles, and a converged filter has to agree again before it moves map <- odom.
    char text[160];
    std::snprintf(text, sizeof text, "odometry jumped by %.2f m and %.1f deg between two readings", step.translation().head<2>().norm(),
                  std::abs(yawOf(step.linear())) * 180.0 / M_PI);
    m.pending_warnings.emplace_back(text);
    m.agreeing_updates = 0;
  }
  m.odom = T_odom_base;
  if (!m.last_odom) m.last_odom = T_odom_base;
  if (!m.odom_start) {
    m.odom_start = planarPose(T_odom_base);
    if (m.prior.active()) m.evidence.setPrior(&m.prior, *m.odom_start);
  }
  // The particles move when they are next weighed (AMCL does the same): the motion between
  // two weighings as one increment, with its noise, instead of one per odometry reading.
}

void ParticleFilter::Impl::applyMotion() {
  if (!last_odom) return;
  // Paper Eq. (u_R): the increment between the odometry poses, in the base frame.
  const Eigen::Isometry3d u = last_odom->inverse() * odom;
  last_odom = odom;
  const double dx = u.translation().x(), dy = u.translation().y(), dyaw = yawOf(u.linear());
  const double trans = std::hypot(dx, dy);
  if (trans == 0.0 && dyaw == 0.0) return;
  const auto& c = config;
  const double sigma_xy = c.motion_noise_xy_per_m * trans + 0.002;
  const double sigma_yaw = c.motion_noise_yaw_per_rad * std::abs(dyaw) + c.motion_noise_yaw_per_m_rad * trans + 0.001;
  std::normal_distribution<double> n(0.0, 1.0);
  for (auto& p : particles) {
    const double ex = dx + sigma_xy * n(rng), ey = dy + sigma_xy * n(rng);
    const double cy = std::cos(p.yaw), sy = std::sin(p.yaw);
    p.x += cy * ex - sy * ey;
    p.y += sy * ex + cy * ey;
    p.yaw = wrapAngle(p.yaw + dyaw + sigma_yaw * n(rng));
    p.room = rooms.roomAt(p.x, p.y);
  }
}

std::vector<detail::Observation> ParticleFilter::Impl::observe(const std::vector<planes::ObservedPlane>& walls,
                                                               std::vector<std::string>* warnings) const {
  // The observations in the yaw-free base frame: shared by every particle.
  const Eigen::Matrix3d tilt = tiltOf(odom.linear());
  const Eigen::Matrix3d R_bl = tilt * T_base_lidar.linear();
  const Eigen::Vector3d t_bl = tilt * T_base_lidar.translation();
  std::vector<detail::Observation> observations;
  for (const auto& w : walls) {
    if (!w.normal.allFinite() || !std::isfinite(w.d) || w.normal.norm() < 0.5) {
      if (warnings) warnings->push_back("skipped a wall plane with non-finite parameters");
      continue;
    }
    detail::Observation o;
    o.normal_base = R_bl * w.normal.normalized();
    o.d_offset = w.d - o.normal_base.dot(t_bl);
    o.azimuth_base = std::atan2(o.normal_base.y(), o.normal_base.x());
    o.elevation = std::asin(std::clamp(o.normal_base.z(), -1.0, 1.0));
    const Eigen::Vector3d centroid = R_bl * w.centroid + t_bl;
    o.centroid_base = centroid.allFinite() ? centroid.head<2>() : Eigen::Vector2d(-o.d_offset * o.normal_base.head<2>());
    o.range_m = centroid.allFinite() ? centroid.norm() : std::abs(o.d_offset);
    o.extent_m = std::isfinite(w.extent_m) && w.extent_m > 0.0 ? w.extent_m : 0.0;
    o.support = std::max(1, w.inliers);
    const Eigen::Vector3d middle = R_bl * w.wall_span_middle + t_bl;
    if (middle.allFinite() && std::isfinite(w.wall_span_m) && w.wall_span_m > 0.0)
      o.span_middle_base = middle.head<2>(), o.wall_span_m = w.wall_span_m;
    // The support's heights about their middle (not the centroid's height: plane_extraction.hpp).
    const double z_middle = (R_bl * w.heightMiddleOrCentroid() + t_bl).z();
    if (std::isfinite(z_middle) && std::isfinite(w.height_extent_m) && w.height_extent_m > 0.0)
      o.z_low = z_middle - 0.5 * w.height_extent_m, o.z_high = z_middle + 0.5 * w.height_extent_m;
    observations.push_back(o);
  }
  if (!detail::positionFixedByPlanes(observations))
    for (auto& o : observations) o.end_scored = true;
  return observations;
}

std::pair<double, int> ParticleFilter::score(double x, double y, double yaw,
                                             const std::vector<planes::ObservedPlane>& walls) const {
  Particle p;
  p.x = x, p.y = y, p.yaw = yaw, p.room = impl_->rooms.roomAt(x, y);
  const auto match = detail::matchObservations(p, impl_->baseZ(), impl_->observe(walls, nullptr), impl_->rooms, impl_->config);
  return {match.log_likelihood, match.associated};
}

bool ParticleFilter::wantsObservations() const { return impl_->shouldWeigh(); }

double ParticleFilter::pathScore(double x, double y, double yaw) const {
  return impl_->evidence.logLikelihoodOf({x, y, yaw}, planarPose(impl_->odom));
}

RangeProfileConfig profileConfig(const ParticleFilterConfig& config) {
  RangeProfileConfig c;
  c.min_height_m = config.free_space_band_low_m;
  c.max_height_m = config.free_space_band_high_m;
  c.bin_deg = config.free_space_bin_deg;
  return c;
}

void setTurnSkew(RangeProfile& profile, const Eigen::Vector3d& moved, bool deskewed, const ParticleFilterConfig& config) {
  const double half_m = 0.5 * moved.head<2>().norm(), half_rad = 0.5 * std::abs(moved.z());
  profile.skew_m = deskewed ? config.motion_noise_xy_per_m * half_m : half_m;
  profile.skew_yaw_rad =
      deskewed ? config.motion_noise_yaw_per_rad * half_rad + config.motion_noise_yaw_per_m_rad * half_m : half_rad;
}

UpdateReport ParticleFilter::update(const std::vector<planes::ObservedPlane>& walls, const RangeProfile* profile) {
  auto& m = *impl_;
  m.profile = profile;
  UpdateReport report;
  report.warnings.swap(m.pending_warnings);
  const std::vector<detail::Observation> observations = m.observe(walls, &report.warnings);
  report.observations = static_cast<int>(observations.size());
  const bool weigh = m.shouldWeigh();
  ++m.scans_since_weighing;
  if (report.observations < m.config.min_observations || !weigh) {
    report.converged = m.T_map_odom.has_value();
    return report;  // too little to weigh by, or nothing new: predict only
  }
  report.weighed = true;
  m.particles_version = Impl::nextParticlesVersion();  // they move, are weighed, drawn, resampled below
  m.applyMotion();
  m.odom_at_last_weighing = m.odom;
  m.scans_since_weighing = 0;
  const double z = m.baseZ();
  // Sensor resetting's poses from this scan (paper: beyond it), then the weighing (paper,
  // "Update"), then the path evidence (beyond the paper) and what it decides.
  const std::vector<detail::Hypothesis> hyps = m.seedHypotheses(observations, z, report);
  bool annealing = false;
  const double best_raw = m.weigh(observations, z, annealing);
  detail::PathVerdict path = m.askThePath(observations, hyps, z, report);
  const bool decisive = path.has_best && path.pose_fixed && path.margin >= m.config.evidenceMargin();
  m.resetFromTheScan(hyps, best_raw, annealing, path, decisive, report);
  m.weighed_once = true;
  if (decisive && !m.T_map_odom) m.followThePath(path, report);
  std::vector<double> w = m.normalisedWeights();
  m.best = m.heaviest();
  double sum2 = 0;
  for (double v : w) sum2 += v * v;
  report.ess = 1.0 / sum2;
  // Convergence (paper, "Initial Transformation Estimation"), then resampling.
  if (m.checkConvergence(observations, z, path, decisive, w, m.mean(w), report)) w = m.normalisedWeights();
  m.resampleAfter(w, report);
  return report;
}

bool ParticleFilter::converged() const { return impl_->T_map_odom.has_value(); }
std::optional<Eigen::Isometry3d> ParticleFilter::T_map_odom() const { return impl_->T_map_odom; }

Eigen::Isometry3d ParticleFilter::T_map_base() const {
  const auto& m = *impl_;
  if (m.T_map_odom) return *m.T_map_odom * m.odom;
  // The particles' mean, moved on by the odometry since they were last weighed.
  const detail::Pose2 pending = m.last_odom ? planarPose(m.last_odom->inverse() * m.odom) : detail::Pose2::Zero();
  const detail::Pose2 now = detail::compose(m.currentMean(), pending);
  Particle p;
  p.x = now.x(), p.y = now.y(), p.yaw = now.z();
  return m.poseOf(p);
}

const std::vector<Particle>& ParticleFilter::particles() const { return impl_->particles; }  // as last weighed
const Particle& ParticleFilter::best() const { return impl_->particles[impl_->best]; }
std::uint64_t ParticleFilter::particlesVersion() const { return impl_->particles_version; }

std::uint64_t ParticleFilter::Impl::nextParticlesVersion() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

int ParticleFilter::estimateRoom() const {
  const Eigen::Vector3d t = T_map_base().translation();
  return impl_->rooms.roomAt(t.x(), t.y());
}

namespace detail {

PathEvidence::WindowFit FilterAccess::windowFit(const ParticleFilter& f, const Pose2& map_pose) {
  return f.impl_->evidence.windowFit(map_pose, planarPose(f.impl_->odom));
}

void FilterAccess::fitPlaces(const ParticleFilter& f, UpdateReport& report) { f.impl_->fitPlaces(report); }

PathVerdict FilterAccess::everyFitVerdict(ParticleFilter& f, const std::vector<planes::ObservedPlane>& walls) {
  auto& m = *f.impl_;
  const Pose2 odom = planarPose(m.odom);
  const PathVerdict before = m.evidence.verdict(odom);
  if (before.has_best) m.evidence.proposeEveryFit(m.observe(walls, nullptr), m.baseZ(), odom, before.best);
  return m.evidence.verdict(odom);
}

}  // namespace detail

}  // namespace bimloc::pf
