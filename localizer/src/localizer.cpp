// The Localizer (bimloc/localizer.hpp): one step of the paper's pipeline, from the lidar's
// points to the search (pf/) and the S-Graph's tracking (sgraph/), and the hand-over between them.
#include "localizer_impl.hpp"

namespace bimloc {
namespace detail {

// Weighted covariance of the particles' (x, y, yaw) about their weighted mean.
Eigen::Matrix3d particleCovariance(const pf::ParticleFilter& filter) {
  const auto& particles = filter.particles();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  if (particles.empty()) return Eigen::Matrix3d::Identity();
  double top = -INFINITY;
  for (const auto& p : particles) top = std::max(top, p.log_weight);
  double sum = 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double s = 0, c = 0;
  std::vector<double> weights;  // each exp once: both passes need it
  weights.reserve(particles.size());
  for (const auto& p : particles) {
    const double w = weights.emplace_back(std::exp(p.log_weight - top));
    sum += w, mean.x() += w * p.x, mean.y() += w * p.y, s += w * std::sin(p.yaw), c += w * std::cos(p.yaw);
  }
  mean.head<2>() /= sum;
  mean.z() = std::atan2(s, c);
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const auto& p = particles[k];
    const double w = weights[k] / sum;
    const Eigen::Vector3d e(p.x - mean.x(), p.y - mean.y(), wrapAngle(p.yaw - mean.z()));
    cov += w * e * e.transpose();
  }
  return cov;
}

}  // namespace detail

using detail::particleCovariance;

const char* toString(LocalizerMethod method) {
  switch (method) {
    case LocalizerMethod::SGraph: return "sgraph";
    case LocalizerMethod::Pf: return "pf";
    case LocalizerMethod::PfNoRooms: return "pf-no-rooms";
    case LocalizerMethod::Amcl: return "amcl";
    case LocalizerMethod::Ndt: return "ndt";
  }
  return "?";
}

std::optional<LocalizerMethod> methodFromString(const std::string& name) {
  if (name == "sgraph") return LocalizerMethod::SGraph;
  if (name == "pf") return LocalizerMethod::Pf;
  if (name == "pf-no-rooms") return LocalizerMethod::PfNoRooms;
  if (name == "amcl") return LocalizerMethod::Amcl;
  if (name == "ndt") return LocalizerMethod::Ndt;
  return std::nullopt;
}

bool isPeer(LocalizerMethod method) { return method == LocalizerMethod::Amcl || method == LocalizerMethod::Ndt; }

const char* toString(LocalizationState state) {
  switch (state) {
    case LocalizationState::Searching: return "searching";
    case LocalizationState::Converged: return "converged";
    case LocalizationState::Tracking: return "tracking";
    case LocalizationState::Lost: return "lost";
  }
  return "?";
}

Localizer::Localizer(const bim::Building& building, const Eigen::Isometry3d& T_base_lidar, const LocalizerConfig& config)
    : impl_(std::make_unique<Impl>(building, T_base_lidar, config)) {
  Impl& m = *impl_;
  if (config.storey.empty()) {
    m.storeys = pf::StoreyBank::candidateStoreys(building);
    if (m.storeys.empty()) throw std::invalid_argument("no storey of the plan has both walls and rooms");
    if (isPeer(config.method) && m.storeys.size() > 1)
      throw std::invalid_argument(std::string(toString(config.method)) + " localizes on one storey's map: give the storey (" +
                                  std::to_string(m.storeys.size()) + " storeys could hold the robot)");
  } else {
    const bim::Storey* storey = building.findStorey(config.storey);
    if (!storey) throw std::invalid_argument(building.storeyLookupError(config.storey));
    m.storeys = {static_cast<std::size_t>(storey - building.storeys.data())};
  }
  if (isPeer(config.method)) {
    const bim::Storey& storey = building.storeys.at(m.storeys.front());
    m.peer = config.method == LocalizerMethod::Amcl ? peers::makeAmcl(storey, m.T_base_lidar, m.config.amcl, m.config.seed)
                                                    : peers::makeNdt(storey, m.T_base_lidar, m.config.ndt, m.config.seed);
    m.filter_active = false;
    return;
  }
  for (std::size_t s = 0; s < m.standing.added.size(); ++s)
    if (m.standing.added[s] > 0)
      m.warnings.push_back("storey '" + building.storeys[s].name + "': " + std::to_string(m.standing.added[s]) +
                           " walls filed under other storeys stand in its wall band: added to its map");
  m.bank = std::make_unique<pf::StoreyBank>(m.mapFor(m.storeys), m.storeys, m.T_base_lidar, m.config.pf);
}

Localizer::~Localizer() = default;
Localizer::Localizer(Localizer&&) noexcept = default;

void Localizer::observeAltitude(double stamp_s, double altitude_m, double sigma_m) {
  if (!std::isfinite(stamp_s) || !std::isfinite(altitude_m) || !std::isfinite(sigma_m) || sigma_m < 0) return;  // no reading
  if (!impl_->altitude_reference_s) impl_->altitude_reference_s = stamp_s;
  impl_->altitude = storeys::AltitudeReading{stamp_s, altitude_m, sigma_m, stamp_s - *impl_->altitude_reference_s};
}

LocalizationResult Localizer::step(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<Eigen::Vector3f>& points_lidar) {
  return step(stamp_s, T_odom_base, PointSource([&points_lidar] { return points_lidar; }));
}

LocalizationResult Localizer::step(double stamp_s, const Eigen::Isometry3d& T_odom_base, const PointSource& points_lidar) {
  Impl& m = *impl_;
  LocalizationResult r;
  r.stamp_s = stamp_s;
  if (m.peer) {
    m.stepPeer(T_odom_base, points_lidar, r);
    return r;
  }
  if (!m.base_height_m) m.firstStep(T_odom_base, r);
  m.places_due = false;
  m.odom_z = T_odom_base.translation().z();
  if (m.altitude && std::isfinite(m.odom_z)) m.altitude_mean.add(*m.altitude, m.odom_z);
  // predict -> follow the storey -> observe (only what a stage will look at) -> track ->
  // search -> hand over or lose -> describe
  Eigen::Isometry3d odom = m.levelled(T_odom_base);
  if (m.filter_active) m.bank->predict(odom);
  m.follow(stamp_s, odom, r);
  odom = m.levelled(T_odom_base);  // an arrival levels it anew
  const PlanarPose odom_now = planarPose(odom);
  std::vector<planes::ObservedPlane> walls;
  pf::RangeProfile profile;  // for the filter's free-space evidence (pf/range_profile.hpp)
  if (m.wantsPoints(odom)) {
    const std::vector<Eigen::Vector3f> points = points_lidar();
    walls = planes::extractPlanes(points, m.config.planes).walls;
    if (m.filter_active && m.config.pf.free_space_evidence) {
      profile = pf::rangeProfile(points, m.T_base_lidar, pf::profileConfig(m.config.pf));
      // The turn spans the interval since the last step, stamped at its middle: its rays are off
      // the stamp's pose by up to half the motion over it (range_profile.hpp).
      // De-skewed, only the odometry's own error over it is left.
      if (m.last_odom) pf::setTurnSkew(profile, between(*m.last_odom, odom_now), m.config.points_deskewed, m.config.pf);
    }
    r.used_points = true;
    r.walls_observed = static_cast<int>(walls.size());
  }
  m.last_odom = odom_now;
  if (m.tracker) m.track(stamp_s, odom, walls, r);
  // Off the floor (on the stairs), the storey's walls are not where the filter looks for them.
  if (m.filter_active && !m.follower.climbing()) m.search(walls, profile, r);
  if (m.usesTracker() && m.filter_active && m.bank->converged()) m.handOver(stamp_s, odom, walls, r);
  m.describe(r);
  if (m.filter_active && r.state == LocalizationState::Searching) {
    m.keepPlaces(T_odom_base, r);
    m.suggestGoal(T_odom_base, r);
  } else {
    m.places.clear(), m.goal.reset(), m.spent_count.reset();
  }
  return r;
}

bool Localizer::Impl::wantsPoints(const Eigen::Isometry3d& T_odom_base) const {
  return (filter_active && bank->wantsObservations()) || (tracker && tracker->wantsObservations(T_odom_base));
}

// The S-Graph's keyframe (paper, "S-Graph based Localization"); a loss starts a new search.
void Localizer::Impl::track(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<planes::ObservedPlane>& walls,
                            LocalizationResult& r) {
  const bool was_lost = lost();
  last_track = tracker->addScan(stamp_s, T_odom_base, walls);
  for (const auto& w : last_track->warnings) r.warnings.push_back("sgraph: " + w);
  r.sgraph = last_track;
  if (last_track->covariance) track_covariance = *last_track->covariance;
  if (last_track->keyframe_added && last_track->plan_walls_matched >= config.sgraph.min_plan_associations && !lost())
    arrival_unconfirmed = false;
  if (!was_lost && lost()) {
    ++losses;
    if (follower.climbing()) {
      pending_search = true;  // on the stairs: search once on a floor
    } else {
      searchAgain(T_odom_base, r);
    }
  } else if (was_lost && !lost()) {
    filter_active = false;  // the tracker found the plan again by itself: the search is moot
    pending_search = false;
  }
}

void Localizer::Impl::search(const std::vector<planes::ObservedPlane>& walls, const pf::RangeProfile& profile, LocalizationResult& r) {
  const std::optional<storeys::AltitudeReading> mean = altitude_mean.at(odom_z);
  if (mean && bank->storeys().size() > 1) {
    // The altitude weighs the storeys the search still considers (those it rules out are not).
    std::vector<double> ll(building.storeys.size(), 0.0);
    for (const std::size_t s : bank->storeys())
      ll[s] = storeys::altitudeLogLikelihood(building, s, *mean, *base_height_m, config.storeys);
    bank->setStoreyLogLikelihoods(std::move(ll));
  }
  pf::StoreyBankReport report = bank->update(walls, &profile);
  // The places the report lists (while not converged), each a fitted pose, not a candidate of
  // the path evidence's wide model: the filter has decided with the latter already. Advice, so
  // at a stated rate (GuideConfig::places_interval_s); 1e-6 s: stamps are sums of float steps.
  if (report.filter.weighed && r.stamp_s - places_fitted_s >= config.guide.places_interval_s - 1e-6) {
    pf::detail::FilterAccess::fitPlaces(bank->filter(), report.filter);
    places_fitted_s = r.stamp_s;
    places_due = true;
  }
  for (const auto& w : report.filter.warnings) r.warnings.push_back("pf: " + w);
  r.filter = std::move(report);
  if (bank->converged() && !convergence_stamp) convergence_stamp = r.stamp_s;
}

// Paper: "When the particle filter provides the initial pose estimation, S-Graphs starts
// creating its first robot-tracking layer": the tracker starts from the filter's map <- odom,
// with this scan as its first keyframe.
void Localizer::Impl::handOver(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<planes::ObservedPlane>& walls,
                               LocalizationResult& r) {
  tracked_storey = bank->storey();
  const bim::Storey& storey = building.storeys.at(*tracked_storey);
  tracker = std::make_unique<sgraph::SGraphTracker>(storey, T_base_lidar, config.sgraph, *bank->T_map_odom());
  filter_active = false;
  track_covariance = particleCovariance(bank->filter());
  last_track = tracker->addScan(stamp_s, T_odom_base, walls);
  for (const auto& w : last_track->warnings) r.warnings.push_back("sgraph: " + w);
  r.sgraph = last_track;
  if (last_track->covariance) track_covariance = *last_track->covariance;
}

// The tracker lost the plan: the filter searches again on the tracked storey, its particles
// around the last tracked pose (the tracker keeps going too, and may find the plan first).
// `T_odom_base`: this step's (levelled) odometry, which the new filter is given before its
// first update, as every filter is (step() predicted the old one this step).
void Localizer::Impl::searchAgain(const Eigen::Isometry3d& T_odom_base, LocalizationResult& r) {
  pf::ParticleFilterConfig c = config.pf;
  c.prior_rooms.clear();
  c.prior_pose = planarPose(last_track->T_map_base);
  // Just arrived by the stairs and the new storey's walls never confirmed: the landing is the
  // prior (the pose carried across, a flight's odometry off it).
  c.prior_sigma_m = arrival_unconfirmed ? config.storeys.arrival_sigma_m : config.relocalize_sigma_m;
  c.prior_sigma_yaw_deg = arrival_unconfirmed ? config.storeys.arrival_sigma_yaw_deg : config.relocalize_sigma_yaw_deg;
  pending_search = false;
  c.seed += static_cast<std::uint64_t>(losses);  // a fresh draw per search
  // The place is known to within the prior: what is left to settle is the pose within it, and
  // that takes waiting for walls, not a sharper test between places. The wall-line rule (a
  // test between look-alike places) converged within seconds among the furniture that made
  // the tracker give up, 0.3-0.4 m off (Duplex Level 1); without it the search waits for the
  // walls that fix the pose.
  c.match_wall_lines = false;
  bank = std::make_unique<pf::StoreyBank>(building, std::vector<std::size_t>{*tracked_storey}, T_base_lidar, c);
  // Without it the first weighing placed its scan at the odometry's origin: in the path
  // evidence's window (a wrong path for every place) and, had that weighing converged, in
  // map <- odom (12.5 m off on StoreyChange's landing with one agreeing weighing).
  bank->predict(T_odom_base);
  filter_active = true;
  r.warnings.push_back("tracking lost: searching again within " + std::to_string(c.prior_sigma_m) + " m of the last pose" +
                       (arrival_unconfirmed ? " (the new storey's walls not confirmed after the stairs)" : ""));
}

// The first step: the base's height above its floor (the odometry starts on the floor), and
// with an altitude and no storey given, the storeys it rules out are not searched.
void Localizer::Impl::firstStep(const Eigen::Isometry3d& T_odom_base, LocalizationResult& r) {
  const double z = T_odom_base.translation().z();
  base_height_m = std::isfinite(z) ? z : 0.0;
  if (!altitude || !config.storey.empty() || storeys.size() < 2) return;
  const std::vector<std::size_t> kept = storeys::storeysAtAltitude(building, storeys, *altitude, *base_height_m, config.storeys);
  if (kept.empty()) {
    r.warnings.push_back("altitude " + std::to_string(altitude->altitude_m) + " m fits no storey's floor: not used to choose the storey");
  } else if (kept.size() < storeys.size()) {
    storeys = kept;
    bank = std::make_unique<pf::StoreyBank>(mapFor(storeys), storeys, T_base_lidar, config.pf);
  }
}

const LocalizerConfig& Localizer::config() const { return impl_->config; }
const pf::StoreyBank* Localizer::filter() const { return impl_->bank.get(); }
const sgraph::SGraphTracker* Localizer::tracker() const { return impl_->tracker.get(); }
std::vector<Localizer::StoreyGraph> Localizer::storeyGraphs() const { return impl_->graphs; }
const std::vector<StoreyLink>& Localizer::storeyLinks() const { return impl_->links; }
const std::vector<std::string>& Localizer::warnings() const { return impl_->warnings; }

}  // namespace bimloc
