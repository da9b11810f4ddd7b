// What one step of the Localizer reports (state, pose, covariance, room), and the peers' step.
#include "localizer_impl.hpp"

namespace bimloc {

using detail::particleCovariance;

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

}  // namespace bimloc
