// Localizer::Impl's storey following (issue 31): the robot's arrival on another storey, and
// the search while it climbs (docs/storey_following.md).
#include "localizer_impl.hpp"

namespace bimloc {

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

}  // namespace bimloc
