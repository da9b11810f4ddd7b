#include <bimloc/localizer.hpp>

#include <bimloc/geometry/planar_pose.hpp>

#include <bimloc/bim/standing_walls.hpp>

#include "peers/peer.hpp"
#include "pf/filter_access.hpp"
#include "storeys/altitude_mean.hpp"
#include "storeys/landing_rooms.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace bimloc {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The stages' seeds from the one seed: the same derivation the bench used before the
// localizer owned the loop, so runs keep their bytes.
LocalizerConfig seeded(LocalizerConfig c) {
  c.pf.seed = c.seed * 0x9E3779B97F4A7C15ull + 11;
  c.planes.seed = c.seed;
  c.pf.use_rooms = c.method != LocalizerMethod::PfNoRooms;
  return c;
}

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

}  // namespace

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

struct Localizer::Impl {
  // The plan as the robot senses it: each storey with the walls of other storeys that stand in
  // its band (bim/standing_walls.hpp; empty with storeys.standing_walls false); every stage
  // reads `building`, which is this, or the plan as filed when it is off.
  bim::StandingWallsReport standing;
  bim::Building sensed;
  const bim::Building& building;
  // The plan as filed: a search over several storeys weighs each by the walls the plan files
  // under it. A wall standing in two storeys' bands is evidence for both alike, and on split
  // levels (Jesse.1) the standing walls make two storeys' maps nearly one: the walls as filed
  // are what the plan says tells its storeys apart (docs/multi_storey.md). One storey's search
  // (given, decided, arrived on) and its tracking use `building`.
  const bim::Building& filed;
  const bim::Building& mapFor(const std::vector<std::size_t>& candidates) const {
    return candidates.size() > 1 ? filed : building;
  }
  Eigen::Isometry3d T_base_lidar;
  LocalizerConfig config;
  std::vector<std::size_t> storeys;  // the candidates of the first search
  std::optional<storeys::AltitudeReading> altitude;  // the latest observeAltitude(), if any
  std::optional<double> altitude_reference_s;        // the first reading's stamp: its drift counts from there
  storeys::AltitudeMean altitude_mean;               // the readings averaged (storeys/altitude_mean.hpp)
  double odom_z = 0;                                 // the odometry's height on this step
  std::unique_ptr<pf::StoreyBank> bank;            // the current (or last) search (not for peers)
  std::unique_ptr<peers::PeerLocalizer> peer;      // methods Amcl, Ndt
  std::optional<Eigen::Isometry3d> peer_T_map_odom;  // the peer's, since it converged
  bool peer_converged = false;
  bool filter_active = true;                       // the filter runs on this step
  std::unique_ptr<sgraph::SGraphTracker> tracker;  // since the first hand-over
  std::optional<sgraph::SGraphResult> last_track;  // the tracker's last answer
  Eigen::Matrix3d track_covariance = Eigen::Matrix3d::Identity();  // of its last solved keyframe
  // The filter's particle covariance under its particles' version (describe(), every step).
  mutable std::optional<std::pair<std::uint64_t, Eigen::Matrix3d>> covariance_at;
  std::optional<double> convergence_stamp;
  std::optional<std::size_t> tracked_storey;
  int losses = 0;
  std::vector<std::string> warnings;
  // Storeys (issue 31). The stages see the odometry levelled: its z less z_shift_m, so that on
  // the storey the robot stands on it reads base_height_m, as on the start storey (the filter
  // puts the base at the storey's elevation + the odometry's z).
  storeys::StoreyFollower follower;
  std::optional<double> base_height_m;  // the odometry's z at the first step: base_link above the floor
  double z_shift_m = 0;
  std::optional<PlanarPose> last_odom;  // the last step's odometry: how far a turn may be skewed
  bool pending_search = false;      // the tracker lost the plan on the stairs: search once off them
  bool arrival_unconfirmed = false;  // the tracker started by an arrival has not matched the new storey's walls yet
  std::vector<StoreyLink> links;
  std::vector<StoreyGraph> graphs;  // the graphs of the storeys left
  std::vector<std::unique_ptr<sgraph::SGraphTracker>> retired;  // ... owned here
  // Where to look next (guide/): the places of the last weighing as map <- odom (which odometry
  // leaves fixed), each with its margin; the planner of the storey they are on; the goal kept
  // between plannings, in the odom frame.
  struct KeptPlace {
    PlanarPose T_map_odom = PlanarPose::Zero();
    double margin = 0;
  };
  std::vector<KeptPlace> places;
  std::size_t places_storey = 0;
  std::unique_ptr<guide::GoalPlanner> planner;
  std::size_t planner_storey = 0;
  std::optional<guide::LookGoal> goal;
  std::vector<KeptPlace> goal_places;  // the places the goal was planned for
  std::size_t goal_planned_count = 0;  // how many places there were when the goal was first planned
  // Set when a goal was reached with no place ruled out since it was planned: the place count
  // then. No new goal until the count falls below it.
  std::optional<std::size_t> spent_count;
  double goal_stamp_s = -1e300;
  double places_fitted_s = -1e300;  // when the places were last fitted (GuideConfig::places_interval_s)
  bool places_due = false;          // ... on this step: the kept places are replaced

  Impl(const bim::Building& b, const Eigen::Isometry3d& mount, const LocalizerConfig& c)
      : sensed(c.storeys.standing_walls ? bim::withStandingWalls(b, {}, &standing) : bim::Building{}),
        building(c.storeys.standing_walls ? sensed : b), filed(b), T_base_lidar(mount), config(seeded(c)),
        follower(building, c.storeys) {}

  bool usesTracker() const { return config.method == LocalizerMethod::SGraph; }
  bool lost() const { return tracker && tracker->state() == sgraph::TrackingState::Lost; }
  // Steps of Localizer::step, in order.
  bool wantsPoints(const Eigen::Isometry3d& T_odom_base) const;
  void track(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<planes::ObservedPlane>& walls, LocalizationResult& r);
  void search(const std::vector<planes::ObservedPlane>& walls, const pf::RangeProfile& profile, LocalizationResult& r);
  void handOver(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<planes::ObservedPlane>& walls, LocalizationResult& r);
  void searchAgain(const Eigen::Isometry3d& T_odom_base, LocalizationResult& r);
  Eigen::Isometry3d levelled(const Eigen::Isometry3d& T_odom_base) const {
    Eigen::Isometry3d T = T_odom_base;
    T.translation().z() -= z_shift_m;
    return T;
  }
  void firstStep(const Eigen::Isometry3d& T_odom_base, LocalizationResult& r);
  void follow(double stamp_s, const Eigen::Isometry3d& odom, LocalizationResult& r);
  void followSearch(double stamp_s, const Eigen::Isometry3d& odom, LocalizationResult& r);
  void arrive(const storeys::StoreyArrival& a, double stamp_s, const Eigen::Isometry3d& odom, LocalizationResult& r);
  void describe(LocalizationResult& r) const;
  void keepPlaces(const Eigen::Isometry3d& T_odom_base, const LocalizationResult& r);
  void suggestGoal(const Eigen::Isometry3d& T_odom_base, LocalizationResult& r);
  static bool samePlaces(const std::vector<KeptPlace>& a, const std::vector<KeptPlace>& b);
  void placeInRoom(LocalizationResult& r) const;
  void stepPeer(const Eigen::Isometry3d& T_odom_base, const PointSource& points_lidar, LocalizationResult& r);
};

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
    if (!storey) throw std::invalid_argument("no storey '" + config.storey + "' in the plan");
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

// Whether the robot arrived on another storey: its height on the tracked storey (the levelled
// odometry's, or the altitude when that rules the tracked storey out: an odometry without
// height) and the plan's stairs (storeys::StoreyFollower).
void Localizer::Impl::follow(double stamp_s, const Eigen::Isometry3d& odom, LocalizationResult& r) {
  if (!config.storeys.follow) return;
  std::optional<Eigen::Isometry3d> T_map_odom;
  std::size_t storey = 0;
  if (tracker && tracked_storey) {
    T_map_odom = tracker->T_map_odom(), storey = *tracked_storey;
  } else if (!usesTracker() && bank->converged()) {
    T_map_odom = bank->T_map_odom(), storey = *bank->storey();
  }
  if (!T_map_odom) return followSearch(stamp_s, odom, r);
  Eigen::Vector3d base = (*T_map_odom * odom).translation();
  // The altitude stands in for the height only when the odometry shows none (2-D odometry: still
  // on the tracked floor while the altitude rules that out). An odometry that climbed keeps its
  // own height: a barometer's per-reading noise (0.1-0.3 m) would never let the height settle.
  if (altitude && storeys::storeysAtAltitude(building, {storey}, *altitude, *base_height_m, config.storeys).empty() &&
      storeys::storeyAtHeight(building, {storey}, base.z(), *base_height_m, config.storeys.floor_tolerance_m) == storey)
    base.z() = altitude->altitude_m;
  if (const auto arrival = follower.step(stamp_s, storey, base, *base_height_m, altitude)) {
    arrive(*arrival, stamp_s, odom, r);
  } else if (pending_search && !follower.climbing()) {
    searchAgain(odom, r);  // lost on the stairs, back on the floor it left
  }
}

// Searching (no pose yet) while the robot climbs: the filter's storeys are at the wrong height
// until it stands again; then the search starts over on the storeys that far above (or below)
// the ones it considered.
void Localizer::Impl::followSearch(double stamp_s, const Eigen::Isometry3d& odom, LocalizationResult& r) {
  const double rise = odom.translation().z() - *base_height_m;
  follower.noteHeight(stamp_s, odom.translation().z());  // no storey tracked: only the height's history
  if (!(std::abs(rise) > config.storeys.floor_tolerance_m) || !follower.settled()) return;
  std::vector<std::size_t> next;
  for (const std::size_t s : bank->storeys()) {
    const auto above = storeys::storeyAtHeight(building, pf::StoreyBank::candidateStoreys(building),
                                               building.storeys[s].elevation_m + *base_height_m + rise, *base_height_m,
                                               config.storeys.floor_tolerance_m);
    if (above && std::find(next.begin(), next.end(), *above) == next.end()) next.push_back(*above);
  }
  if (altitude) {
    const auto kept = storeys::storeysAtAltitude(building, next, *altitude, *base_height_m, config.storeys);
    if (!kept.empty()) next = kept;
  }
  if (next.empty()) return;  // no floor that far up: wait
  z_shift_m += rise;
  // The robot came by a flight: it is at (or a few steps past) the end of one that arrives on
  // these storeys, the search's prior rooms (the start's prior, if any, is moot up here). The
  // reach: the height settles settled_window_s after the last riser, and the search starts
  // then, 1-2 m on at a legged base's 0.5-1 m/s.
  constexpr double kLandingReachM = 2.0;
  pf::ParticleFilterConfig c = config.pf;
  c.prior_rooms = storeys::landingRooms(building, next, rise > 0, kLandingReachM);
  c.prior_pose.reset();
  bank = std::make_unique<pf::StoreyBank>(mapFor(next), next, T_base_lidar, c);
  Eigen::Isometry3d now = odom;
  now.translation().z() -= rise;
  bank->predict(now);
  r.warnings.push_back("the base climbed " + std::to_string(rise) + " m while searching: the search starts again " +
                       std::to_string(next.size()) + " storey(s) " + (rise > 0 ? "up" : "down") +
                       (c.prior_rooms.empty() ? std::string(", over the whole storey")
                                              : ", in the " + std::to_string(c.prior_rooms.size()) + " room(s) at the flights' ends"));
}

// Onto the new storey: the pose carried across (map <- odom kept in x, y, yaw; z on the new
// floor), the odometry levelled there, the old storey's graph kept and a new graph started.
void Localizer::Impl::arrive(const storeys::StoreyArrival& a, double stamp_s, const Eigen::Isometry3d& odom, LocalizationResult& r) {
  Eigen::Isometry3d T_map_odom = tracker && tracked_storey ? tracker->T_map_odom() : *bank->T_map_odom();
  const double rise = odom.translation().z() - *base_height_m;  // the odometry's height over the floor it left
  z_shift_m += rise;
  Eigen::Isometry3d now = odom;
  now.translation().z() -= rise;
  T_map_odom.translation().z() = building.storeys[a.to].elevation_m;
  StoreyLink link;
  link.from_storey = a.from, link.to_storey = a.to, link.flight = a.flight, link.stamp_s = stamp_s;
  link.T_map_base = T_map_odom * now;
  links.push_back(link);
  r.arrival = link;
  const std::string by = a.flight >= 0 ? " by " + building.stairs[static_cast<std::size_t>(a.flight)].name : std::string();
  r.warnings.push_back("arrived on storey '" + building.storeys[a.to].name + "' from '" + building.storeys[a.from].name + "'" + by);
  arrival_unconfirmed = true;
  pending_search = false;
  if (usesTracker()) {
    graphs.push_back({a.from, tracker.get(), link});
    retired.push_back(std::move(tracker));
    tracker = std::make_unique<sgraph::SGraphTracker>(building.storeys[a.to], T_base_lidar, config.sgraph, T_map_odom);
    tracked_storey = a.to;
    filter_active = false;  // a search on the storey left is moot
    return;
  }
  // The filter methods track with their particles: a search on the new storey, the landing its prior.
  pf::ParticleFilterConfig c = config.pf;
  c.prior_rooms.clear();
  c.prior_pose = planarPose(link.T_map_base);
  c.prior_sigma_m = config.storeys.arrival_sigma_m;
  c.prior_sigma_yaw_deg = config.storeys.arrival_sigma_yaw_deg;
  c.seed += static_cast<std::uint64_t>(links.size()) * 7919u;
  bank = std::make_unique<pf::StoreyBank>(building, std::vector<std::size_t>{a.to}, T_base_lidar, c);
  bank->predict(now);
  filter_active = true;
}

void Localizer::Impl::describe(LocalizationResult& r) const {
  r.losses = losses;
  r.convergence_stamp_s = convergence_stamp;
  const bool converged_now = convergence_stamp && *convergence_stamp == r.stamp_s && (r.sgraph || !usesTracker());
  if (tracker && last_track) {
    r.state = lost() ? LocalizationState::Lost : LocalizationState::Tracking;
    r.T_map_base = last_track->T_map_base;
    r.T_map_odom = last_track->T_map_odom * Eigen::Translation3d(0, 0, -z_shift_m);
    r.storey = tracked_storey;
    r.leading_storey = *tracked_storey;
    r.covariance = track_covariance;
  } else {
    r.state = bank->converged() ? LocalizationState::Tracking : LocalizationState::Searching;
    r.T_map_base = bank->T_map_base();
    r.T_map_odom = bank->T_map_odom();
    if (r.T_map_odom) *r.T_map_odom = *r.T_map_odom * Eigen::Translation3d(0, 0, -z_shift_m);
    r.storey = bank->storey();
    r.leading_storey = bank->leader();
    // Asked at every step; the particles change only when weighed.
    const pf::ParticleFilter& filter = bank->filter();
    if (!covariance_at || covariance_at->first != filter.particlesVersion())
      covariance_at.emplace(filter.particlesVersion(), particleCovariance(filter));
    r.covariance = covariance_at->second;
  }
  if (converged_now && r.state == LocalizationState::Tracking) r.state = LocalizationState::Converged;
  placeInRoom(r);
}

// The room of the estimate, on the decided (or leading) storey.
void Localizer::Impl::placeInRoom(LocalizationResult& r) const {
  const bim::Storey& storey = building.storeys.at(r.leading_storey);
  const bim::Room* room = storey.roomAt(r.T_map_base.translation().head<2>());
  r.room = room ? static_cast<int>(room - storey.rooms.data()) : -1;
  r.room_name = room ? room->name : std::string();
}

// A peer (AMCL, NDT) decides by its own criterion; the states mean the same as for the
// paper's method: converged once, tracking while it keeps its criterion, lost when it gives
// the pose up after having had it (map <- odom kept, dead reckoning, until it converges again).
void Localizer::Impl::stepPeer(const Eigen::Isometry3d& T_odom_base, const PointSource& points_lidar, LocalizationResult& r) {
  std::vector<Eigen::Vector3f> points;
  const bool wants = peer->wantsPoints(T_odom_base);
  if (wants) points = points_lidar();
  peers::PeerStep s = peer->step(r.stamp_s, T_odom_base, wants ? &points : nullptr);
  r.used_points = wants;
  for (auto& w : s.warnings) r.warnings.push_back(std::move(w));
  const bool was_converged = peer_converged;
  peer_converged = s.report.converged;
  if (peer_converged) {
    peer_T_map_odom = s.T_map_base * T_odom_base.inverse();
    if (!convergence_stamp) convergence_stamp = r.stamp_s;
  } else if (was_converged) {
    ++losses;
  }
  r.T_map_odom = peer_T_map_odom;
  r.T_map_base = !peer_converged && peer_T_map_odom ? *peer_T_map_odom * T_odom_base : s.T_map_base;
  r.covariance = s.covariance;
  r.losses = losses;
  r.convergence_stamp_s = convergence_stamp;
  r.storey = storeys.front();
  r.leading_storey = storeys.front();
  if (peer_converged)
    r.state = convergence_stamp == r.stamp_s && !was_converged && losses == 0 ? LocalizationState::Converged : LocalizationState::Tracking;
  else
    r.state = convergence_stamp ? LocalizationState::Lost : LocalizationState::Searching;
  r.peer = std::move(s.report);
  placeInRoom(r);
}

// The places of this step's weighing (if it refreshed them, places_interval_s): its best and the
// rivals within the evidence margin, kept as map <- odom so that later steps move them with the
// odometry.
void Localizer::Impl::keepPlaces(const Eigen::Isometry3d& T_odom_base, const LocalizationResult& r) {
  if (!places_due || !r.filter) return;
  const pf::UpdateReport& u = r.filter->filter;
  const PlanarPose odom_inv = inverse(planarPose(T_odom_base));
  places.clear();
  places_storey = r.filter->leader;
  if (!u.path_best) return;
  places.push_back({compose(*u.path_best, odom_inv), 0.0});
  for (const auto& [pose, margin] : u.path_rivals) places.push_back({compose(pose, odom_inv), margin});
}

bool Localizer::Impl::samePlaces(const std::vector<KeptPlace>& a, const std::vector<KeptPlace>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if ((a[i].T_map_odom.head<2>() - b[i].T_map_odom.head<2>()).norm() > 0.5 ||
        std::abs(wrapAngle(a[i].T_map_odom.z() - b[i].T_map_odom.z())) > 10.0 * kDeg)
      return false;
  return true;
}

// The places now and a goal: planned again when the places change, the goal is reached, or it
// is config.guide.replan_interval_s old; kept in the odom frame in between.
void Localizer::Impl::suggestGoal(const Eigen::Isometry3d& T_odom_base, LocalizationResult& r) {
  const PlanarPose odom = planarPose(T_odom_base);
  if (places.size() < 2) {
    goal.reset();
    return;
  }
  for (const auto& p : places) r.places.push_back({compose(p.T_map_odom, odom), p.margin});
  if (!config.guide.enabled) return;
  const bool reached = goal && (goal->T_odom_goal.head<2>() - odom.head<2>()).norm() < config.guide.goal_reached_m;
  // A goal is suggested only where the planner predicts it decides (min_information). Reached
  // with no place ruled out, that prediction failed for these places: no new goal until one is
  // ruled out, and the base goes its own way (the bench: its tour). Planning afresh each time
  // had the base dither between nearby goals that each promised to decide
  // (random_residential_98001 R007: 12 m walked in 48 s, the tour 22 m and a fix at 9 s).
  if (reached && places.size() >= goal_planned_count) spent_count = places.size();
  if (spent_count && places.size() < *spent_count) spent_count.reset();
  if (spent_count) {
    goal.reset();
    return;
  }
  if (!samePlaces(places, goal_places) || reached || r.stamp_s - goal_stamp_s >= config.guide.replan_interval_s) {
    if (!planner || planner_storey != places_storey) {
      planner = std::make_unique<guide::GoalPlanner>(building.storeys.at(places_storey), config.guide);
      planner_storey = places_storey;
    }
    // A goal under way is kept while it still tells the places apart and stays within reach in
    // each: the places change with nearly every weighing, and a new best goal each time had the
    // base turn back and forth between two goals, walking 2 m in 40 s (site_office R104).
    std::optional<double> still;
    if (goal && !reached) still = planner->informationOf(r.places, between(odom, goal->T_odom_goal));
    if (still && *still >= config.guide.min_information)
      goal->information = *still;
    else if ((goal = planner->suggest(r.places, odom)))
      goal_planned_count = places.size();
    goal_places = places;
    goal_stamp_s = r.stamp_s;
  }
  if (!goal) return;
  // The kept goal, seen from now: the motion from the base, and where it is in each place.
  r.goal = *goal;
  r.goal->motion = between(odom, goal->T_odom_goal);
  r.goal->distance_m = r.goal->motion.head<2>().norm();
  r.goal->T_map_goal.clear();
  for (const auto& p : places) r.goal->T_map_goal.push_back(compose(p.T_map_odom, goal->T_odom_goal));
}

const LocalizerConfig& Localizer::config() const { return impl_->config; }
const pf::StoreyBank* Localizer::filter() const { return impl_->bank.get(); }
const sgraph::SGraphTracker* Localizer::tracker() const { return impl_->tracker.get(); }
std::vector<Localizer::StoreyGraph> Localizer::storeyGraphs() const { return impl_->graphs; }
const std::vector<StoreyLink>& Localizer::storeyLinks() const { return impl_->links; }
const std::vector<std::string>& Localizer::warnings() const { return impl_->warnings; }

}  // namespace bimloc
