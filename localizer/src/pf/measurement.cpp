#include "measurement.hpp"

#include <cmath>

namespace bimloc::pf::detail {

MatchResult matchObservations(const Particle& p, double z_base, const std::vector<Observation>& observations,
                              const RoomIndex& rooms, const ParticleFilterConfig& c) {
  MatchResult result;
  const double gate = c.gate_mahalanobis2;
  if (p.room < 0) {
    // Outside every room: the lowest weight there is, below any particle whose observations
    // are all clutter.
    result.log_likelihood = -0.5 * gate * (static_cast<double>(observations.size()) + 1.0) - 10.0;
    return result;
  }
  const auto& landmarks = rooms.landmarks(p.room);
  const double cy = std::cos(p.yaw), sy = std::sin(p.yaw);
  const double inv_az = 1.0 / (c.sigma_azimuth_deg * M_PI / 180.0), inv_el = 1.0 / (c.sigma_elevation_deg * M_PI / 180.0);
  const double inv_d = 1.0 / c.sigma_d_m;
  const double margin_m = c.segment_margin_m;
  for (const auto& o : observations) {
    // The observed normal in the map (a plane moves with a pose: n' = R n).
    const double nx = cy * o.normal_base.x() - sy * o.normal_base.y(), ny = sy * o.normal_base.x() + cy * o.normal_base.y();
    const double azimuth = o.azimuth_base + p.yaw, elevation = o.elevation;
    const bim::WallAxis axis = std::abs(nx) >= std::abs(ny) ? bim::WallAxis::X : bim::WallAxis::Y;
    const Eigen::Vector2d centroid(p.x + cy * o.centroid_base.x() - sy * o.centroid_base.y(),
                                   p.y + sy * o.centroid_base.x() + cy * o.centroid_base.y());
    double best = gate;
    for (const auto& l : landmarks) {
      if (l.axis != axis) continue;  // the paper's semantic classes: x walls with x walls
      // Paper Eq. (plane error): the squared Mahalanobis distance of the minimal planes, with
      // d taken at the particle (the landmark moved to a frame centred on it, axes of the map):
      // compared at the map's origin instead, a heading error of 1 degree would cost 0.17 m of
      // d per 10 m from the origin, and the same view would score worse far from it.
      const double d_landmark = l.d + l.normal.x() * p.x + l.normal.y() * p.y + l.normal.z() * z_base;
      const double e_az = wrapAngle(azimuth - l.azimuth) * inv_az, e_el = (elevation - l.elevation) * inv_el;
      const double e_d = (o.d_offset - d_landmark) * inv_d;
      const double m2 = e_az * e_az + e_el * e_el + e_d * e_d;
      if (m2 >= best) continue;
      // The observed wall's points must lie along the face, not beside its end.
      const double u = (centroid - l.start).dot(l.direction);
      if (u < -margin_m || u > l.length_m + margin_m) continue;
      best = m2;
    }
    // An observation that matches nothing is clutter (the site does not look like the plan
    // yet): it costs what a match at the gate would, so it cannot destroy a good particle.
    if (best < gate) ++result.associated;
    result.log_likelihood += -0.5 * best;
  }
  return result;
}

}  // namespace bimloc::pf::detail
