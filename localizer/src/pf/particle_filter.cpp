// The filter's cycle reads like the paper: predict with odometry -> associate rooms and walls
// -> weight -> resample -> check convergence -> initial transformation map <- odom.
#include <bimloc/pf/particle_filter.hpp>

#include "filter_access.hpp"
#include "hypotheses.hpp"
#include "measurement.hpp"
#include "particle_set.hpp"
#include "path_evidence.hpp"
#include "room_index.hpp"
#include "start_prior.hpp"

#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/geometry/planar_pose.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace bimloc::pf {
namespace {

using detail::near;
using detail::wrapAngle;

// The rotation without its yaw: roll and pitch.
Eigen::Matrix3d tiltOf(const Eigen::Matrix3d& R) {
  return Eigen::AngleAxisd(-yawOf(R), Eigen::Vector3d::UnitZ()).toRotationMatrix() * R;
}

// Odometry jumps beyond these in one step are reported, and spread the particles accordingly.
constexpr double kJumpM = 1.0;
constexpr double kJumpRad = M_PI / 4;

}  // namespace

struct ParticleFilter::Impl {
  const bim::Storey& storey;
  Eigen::Isometry3d T_base_lidar;
  ParticleFilterConfig config;
  detail::RoomIndex rooms;
  detail::StartPrior prior;
  detail::PathEvidence evidence;
  std::optional<detail::Pose2> odom_start;  // the first odometry pose: where the prior applies
  std::mt19937_64 rng;
  std::vector<Particle> particles;
  std::optional<Eigen::Isometry3d> last_odom;
  Eigen::Isometry3d odom = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Isometry3d> T_map_odom;
  int agreeing_updates = 0;
  std::size_t best = 0;
  std::optional<Eigen::Isometry3d> odom_at_last_weighing;
  int scans_since_weighing = 0;
  double anneal = 1.0;
  bool weighed_once = false;
  std::vector<std::string> pending_warnings;  // from predict(), reported by the next update()

  // AMCL-style gate: weigh after enough motion, or after enough scans standing still.
  bool shouldWeigh() const {
    if (!odom_at_last_weighing || scans_since_weighing + 1 >= config.max_static_scans) return true;
    const Eigen::Isometry3d moved = odom_at_last_weighing->inverse() * odom;
    return moved.translation().head<2>().norm() >= config.update_min_translation_m ||
           std::abs(yawOf(moved.linear())) >= config.update_min_rotation_deg * M_PI / 180.0;
  }

  Impl(const bim::Storey& s, const Eigen::Isometry3d& mount, const ParticleFilterConfig& c)
      : storey(s), T_base_lidar(mount), config(c), rooms(s, c.use_rooms, c.neighbour_rooms), prior(s, rooms, c),
        evidence(s, c), rng(c.seed), anneal(c.anneal_start) {
    const auto count = static_cast<std::size_t>(std::max(1, c.particles));
    if (prior.active()) {
      for (std::size_t i = 0; i < count; ++i) particles.push_back(prior.draw(rng));
    } else {
      particles = detail::spreadOverRooms(rooms, count, rng);
    }
  }

  // The start pose a pose now implies, through the odometry since the start.
  detail::Pose2 startOf(const detail::Pose2& now) const {
    if (!odom_start) return now;
    return detail::compose(now, detail::compose(detail::inverse(planarPose(odom)), *odom_start));
  }
  bool admitted(const detail::Pose2& now) const { return !prior.active() || prior.admits(startOf(now)); }

  int inject(const std::vector<detail::Hypothesis>& hyps, std::size_t count, double bonus = 0.0) {
    return detail::inject(particles, hyps, count, bonus, rooms, rng);
  }
  std::size_t heaviest() const { return detail::heaviest(particles); }
  std::vector<double> normalisedWeights() const { return detail::normalisedWeights(particles); }
  Eigen::Vector3d mean(const std::vector<double>& w) const { return detail::weightedMean(particles, w); }
  void resample(const std::vector<double>& w, std::size_t count) {
    best = detail::resample(particles, w, count, best, config.roughening_xy_m, config.roughening_yaw_deg * M_PI / 180.0, rooms, rng);
  }

  double baseZ() const { return storey.elevation_m + odom.translation().z(); }
  void applyMotion();

  std::vector<detail::Observation> observe(const std::vector<planes::ObservedPlane>& walls,
                                           std::vector<std::string>* warnings) const;

  Eigen::Isometry3d poseOf(const Particle& p) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * tiltOf(odom.linear());
    T.translation() = Eigen::Vector3d(p.x, p.y, baseZ());
    return T;
  }

};

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
    observations.push_back(o);
  }
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

UpdateReport ParticleFilter::update(const std::vector<planes::ObservedPlane>& walls) {
  auto& m = *impl_;
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
  m.applyMotion();
  m.odom_at_last_weighing = m.odom;
  m.scans_since_weighing = 0;
  const double z = m.baseZ();
  const double n = static_cast<double>(m.particles.size());
  std::vector<detail::Hypothesis> hyps;
  if (m.config.use_hypotheses) {
    hyps = detail::poseHypotheses(observations, z, m.rooms, m.config, static_cast<std::size_t>(m.config.max_hypotheses));
    if (m.prior.active())  // no pose the prior rules out, not even as a seed
      hyps.erase(std::remove_if(hyps.begin(), hyps.end(), [&](const detail::Hypothesis& h) { return !m.admitted({h.x, h.y, h.yaw}); }),
                 hyps.end());
    report.hypotheses = static_cast<int>(hyps.size());
    if (!m.weighed_once) report.injected = m.inject(hyps, static_cast<std::size_t>(m.config.initial_hypothesis_fraction * n));
    if (report.injected > 0) m.agreeing_updates = 0;
  }

  // Weigh (paper, "Update"): each particle's observations against its room's walls.
  ParticleFilterConfig annealed = m.config;
  annealed.sigma_azimuth_deg *= m.anneal, annealed.sigma_elevation_deg *= m.anneal, annealed.sigma_d_m *= m.anneal;
  annealed.segment_margin_m *= m.anneal;
  const bool annealing = m.anneal > 1.0;
  m.anneal = std::max(1.0, m.anneal * m.config.anneal_rate);
  double best_raw = -1e300;  // the best fit of any particle, at the final (unannealed) sigmas
  for (auto& p : m.particles) {
    const auto match = detail::matchObservations(p, z, observations, m.rooms, annealed);
    if (!annealing) best_raw = std::max(best_raw, match.log_likelihood);
    p.log_weight += m.config.likelihood_power * match.log_likelihood;
    if (m.prior.active() && !m.admitted({p.x, p.y, p.yaw})) p.log_weight -= m.config.likelihood_power * m.config.outside_rooms_penalty;
  }
  const bool tracking = m.T_map_odom.has_value();

  // The path's evidence: this scan joins the window, the scan's best poses and the filter's
  // best particle become candidates.
  const detail::Pose2 odom = planarPose(m.odom);
  m.evidence.addScan(odom, z, observations);
  for (std::size_t k = 0; k < hyps.size() && static_cast<int>(k) < m.config.evidence_proposals; ++k)
    m.evidence.propose({hyps[k].x, hyps[k].y, hyps[k].yaw}, odom);
  const Particle& heaviest = m.particles[m.heaviest()];
  m.evidence.propose({heaviest.x, heaviest.y, heaviest.yaw}, odom);
  detail::PathVerdict path = m.evidence.verdict(odom);
  report.path_margin = path.margin;
  if (path.has_best) report.path_best = path.best;
  report.path_candidates = path.candidates;
  report.path_rivals = path.rivals;
  const bool decisive = path.has_best && path.pose_fixed && path.margin >= m.config.evidenceMargin();
  const double yaw_tol = m.config.converged_yaw_deg * M_PI / 180.0;
  // Sensor resetting: the particles explain the scan clearly worse than the plan can.
  // After convergence the filter tracks (paper: the S-Graph takes over): no more jumps. While
  // the path evidence is decisive, the scan's poses elsewhere are places it has refuted (each
  // was a candidate): only those at its best place may be drawn. A few particles 15 m away,
  // drawn at the heaviest weight, kept the cloud's spread above the convergence radius.
  if (m.weighed_once && !tracking && !hyps.empty() && !annealing &&
      hyps[0].log_likelihood > best_raw + m.config.injection_margin) {
    std::vector<detail::Hypothesis> reset;
    for (const auto& h : hyps)
      if (!decisive || near({h.x, h.y, h.yaw}, path.best, 2.0 * m.config.converged_position_m, 2.0 * yaw_tol)) reset.push_back(h);
    report.injected += m.inject(reset, static_cast<std::size_t>(m.config.injection_fraction * n));
    if (!reset.empty() && !decisive) m.agreeing_updates = 0;  // drawn at the best place: no jump
  }
  m.weighed_once = true;
  std::vector<double> w = m.normalisedWeights();
  Eigen::Vector3d mean = m.mean(w);
  if (decisive && !tracking) {
    // The path fits one place decisively better than any other: a share of the particles goes
    // to its pose, heavier than any (their evidence is the whole window, not one scan). Where
    // the particles are elsewhere, that moves them; where they are already around it, the
    // window's fitted pose tightens the cloud (one scan's planes alone leave it wide).
    detail::Hypothesis h;
    h.x = path.best.x(), h.y = path.best.y(), h.yaw = path.best.z();
    report.injected += m.inject({h}, static_cast<std::size_t>(m.config.evidence_injection_fraction * n),
                                m.config.likelihood_power * m.config.evidenceMargin());
    // The path fits every other place worse by at least the bar: particles elsewhere (a
    // look-alike the scans alone keep alive) pay the bar, tempered as a scan is, at each
    // decisive weighing. They fade over a few weighings instead of holding the cloud's spread,
    // and the convergence test below, open for as long, waited on them for up to 13 s.
    for (auto& p : m.particles)
      if (!near({p.x, p.y, p.yaw}, path.best, 2.0 * m.config.converged_position_m, 2.0 * yaw_tol))
        p.log_weight -= m.config.likelihood_power * m.config.evidenceMargin();
    if (!near(mean, path.best, m.config.converged_position_m, yaw_tol)) m.agreeing_updates = 0;
    w = m.normalisedWeights();
    mean = m.mean(w);
  }
  m.best = m.heaviest();
  double sum2 = 0;
  for (double v : w) sum2 += v * v;
  report.ess = 1.0 / sum2;

  // Convergence (paper, "Initial Transformation Estimation"): the best particle close to the
  // weighted mean, for several updates in a row; and (beyond the paper) the path decisively
  // better explained there than anywhere else.
  const Particle& best = m.particles[m.best];
  report.associated = detail::matchObservations(best, z, observations, m.rooms, m.config).associated;
  double var_xy = 0, var_yaw = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const auto& p = m.particles[i];
    var_xy += w[i] * ((p.x - mean.x()) * (p.x - mean.x()) + (p.y - mean.y()) * (p.y - mean.y()));
    var_yaw += w[i] * wrapAngle(p.yaw - mean.z()) * wrapAngle(p.yaw - mean.z());
  }
  const bool clustered = near({best.x, best.y, best.yaw}, mean, m.config.converged_position_m, yaw_tol) &&
                         std::sqrt(var_xy) < m.config.converged_position_m && std::sqrt(var_yaw) < yaw_tol;
  bool agrees = clustered && (tracking || (decisive && near(mean, path.best, m.config.converged_position_m, yaw_tol)));
  bool searched = true;
  if (agrees && !tracking) {
    // About to count towards convergence: first make sure no look-alike is missing from the
    // candidates, then ask again.
    searched = m.evidence.proposeEveryFit(observations, z, odom, path.best);
    path = m.evidence.verdict(odom);
    report.path_margin = path.margin, report.path_best = path.best, report.path_candidates = path.candidates;
    report.path_rivals = path.rivals;
    agrees = searched && path.pose_fixed && path.margin >= m.config.evidenceMargin() &&
             near(mean, path.best, m.config.converged_position_m, yaw_tol);
  }
  // A scan whose search could not vouch for the rivals checked the verdict against nothing: it
  // neither counts towards convergence nor breaks the run of agreeing ones.
  if (searched) m.agreeing_updates = agrees ? m.agreeing_updates + 1 : 0;
  if (m.agreeing_updates >= m.config.converged_updates) {
    // Paper Eq.: map <- odom = best particle (+) inverse of the odometry pose. After that it
    // follows the filter's weighted mean (tracking, until an S-Graph takes over): smoother
    // than the best particle, which the roughening keeps shaking.
    Particle at = best;
    if (m.T_map_odom) at.x = mean.x(), at.y = mean.y(), at.yaw = mean.z();
    m.T_map_odom = m.poseOf(at) * m.odom.inverse();
  }
  report.converged = m.T_map_odom.has_value();

  const auto tracking_count = static_cast<std::size_t>(std::max(1, m.config.tracking_particles));
  if (m.T_map_odom && m.particles.size() > tracking_count) {
    m.resample(w, tracking_count);
    report.resampled = true;
  } else if (report.ess < m.config.resample_ess_fraction * n) {
    m.resample(w, m.particles.size());
    report.resampled = true;
  } else {
    // Keep the weights bounded: only their differences matter.
    const double top = m.particles[m.best].log_weight;
    for (auto& p : m.particles) p.log_weight -= top;
  }
  return report;
}

bool ParticleFilter::converged() const { return impl_->T_map_odom.has_value(); }
std::optional<Eigen::Isometry3d> ParticleFilter::T_map_odom() const { return impl_->T_map_odom; }

Eigen::Isometry3d ParticleFilter::T_map_base() const {
  const auto& m = *impl_;
  if (m.T_map_odom) return *m.T_map_odom * m.odom;
  // The particles' mean, moved on by the odometry since they were last weighed.
  const detail::Pose2 pending = m.last_odom ? planarPose(m.last_odom->inverse() * m.odom) : detail::Pose2::Zero();
  const detail::Pose2 now = detail::compose(m.mean(m.normalisedWeights()), pending);
  Particle p;
  p.x = now.x(), p.y = now.y(), p.yaw = now.z();
  return m.poseOf(p);
}

const std::vector<Particle>& ParticleFilter::particles() const { return impl_->particles; }  // as last weighed
const Particle& ParticleFilter::best() const { return impl_->particles[impl_->best]; }

int ParticleFilter::estimateRoom() const {
  const Eigen::Vector3d t = T_map_base().translation();
  return impl_->rooms.roomAt(t.x(), t.y());
}

namespace detail {

PathEvidence::WindowFit FilterAccess::windowFit(const ParticleFilter& f, const Pose2& map_pose) {
  return f.impl_->evidence.windowFit(map_pose, planarPose(f.impl_->odom));
}

PathVerdict FilterAccess::everyFitVerdict(ParticleFilter& f, const std::vector<planes::ObservedPlane>& walls) {
  auto& m = *f.impl_;
  const Pose2 odom = planarPose(m.odom);
  const PathVerdict before = m.evidence.verdict(odom);
  if (before.has_best) m.evidence.proposeEveryFit(m.observe(walls, nullptr), m.baseZ(), odom, before.best);
  return m.evidence.verdict(odom);
}

}  // namespace detail

}  // namespace bimloc::pf
