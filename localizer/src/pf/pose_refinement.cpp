#include "pose_refinement.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::pf::detail {

ParticleFilterConfig refinementModel(const ParticleFilterConfig& filter, const PoseRefinementConfig& r) {
  ParticleFilterConfig c = filter;
  const double drift_m = filter.evidence_drift_fraction * r.window_m;
  c.sigma_d_m = std::sqrt(r.range_sigma_m * r.range_sigma_m + filter.evidence_plan_tolerance_m * filter.evidence_plan_tolerance_m +
                          drift_m * drift_m);
  c.use_rooms = false;
  return c;
}

MatchResult matchScanAt(const Eigen::Vector3d& T_map_odom, const RefinementScan& scan, const RoomIndex& every_face,
                        const ParticleFilterConfig& model, double opening_margin_m, std::vector<ObservationMatch>* per_observation,
                        const FaceShortlist* shortlist, double floor) {
  const Eigen::Vector3d p = compose(T_map_odom, scan.odom);
  Particle particle;
  particle.x = p.x(), particle.y = p.y(), particle.yaw = p.z();
  if (shortlist && !shortlist->holds(particle)) shortlist = nullptr;
  // Without the room factor and unpenalised, the room does not change the match: not looked up
  // where the shortlist stands for the index (a lookup per pose and scan of the search).
  particle.room = shortlist ? -1 : every_face.roomAt(p.x(), p.y());
  return matchObservations(particle, scan.z_base, *scan.observations, every_face, model, per_observation,
                           /*out_of_rooms_penalised=*/false, floor, opening_margin_m, shortlist);
}

std::vector<FaceShortlist> windowShortlists(const Eigen::Vector3d& centre, const Eigen::Vector3d& odom_now,
                                            const std::vector<RefinementScan>& scans, const RoomIndex& every_face,
                                            const ParticleFilterConfig& model, const PoseRefinementConfig& r) {
  std::vector<FaceShortlist> lists;
  lists.reserve(scans.size());
  const Eigen::Vector3d T_map_odom = compose(centre, inverse(odom_now));
  for (const auto& s : scans) {
    // The scan's base moves with the pose now, and turns about it: by the offset times the turn.
    const Eigen::Vector3d rel = compose(inverse(odom_now), s.odom);
    const double xy_radius = r.search_m + rel.head<2>().norm() * kShortlistYawRad + 0.01;
    lists.push_back(shortlistFaces(compose(T_map_odom, s.odom), xy_radius, kShortlistYawRad, s.z_base, *s.observations, every_face, model,
                                   r.opening_margin_m));
  }
  return lists;
}

std::vector<Eigen::Vector2d> gridOffsets(const PoseRefinementConfig& r, double min_m) {
  std::vector<Eigen::Vector2d> offsets;
  if (r.grid_step_m <= 0.0) return offsets;
  const int n = static_cast<int>(std::floor(r.search_m / r.grid_step_m));
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j) {
      const Eigen::Vector2d o(i * r.grid_step_m, j * r.grid_step_m);
      if (o.norm() >= min_m - 1e-9 && o.norm() <= r.search_m + 1e-9) offsets.push_back(o);
    }
  std::stable_sort(offsets.begin(), offsets.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.squaredNorm() < b.squaredNorm();
  });
  return offsets;
}

namespace {

// The window's log-likelihood at `pose_now`; or, once it cannot end above `must_exceed`, the
// sum so far (at most must_exceed): every term is <= 0, and in floating point adding one never
// makes a sum grow. Within a scan, its match stops at a floor a micro-unit below what the scan
// may still lose, which covers the rounding of the sum and of the floor itself.
double windowScore(const Eigen::Vector3d& pose_now, const Eigen::Vector3d& odom_now, const std::vector<RefinementScan>& scans,
                   const RoomIndex& faces, const ParticleFilterConfig& model, double opening_margin_m,
                   const std::vector<FaceShortlist>& shortlists, double must_exceed) {
  const Eigen::Vector3d T_map_odom = compose(pose_now, inverse(odom_now));
  double sum = 0;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const double floor = std::isfinite(must_exceed) ? must_exceed - sum - 1e-6 : -std::numeric_limits<double>::infinity();
    const MatchResult m = matchScanAt(T_map_odom, scans[k], faces, model, opening_margin_m, nullptr, &shortlists[k], floor);
    if (m.below_floor) return std::min(sum + m.log_likelihood, must_exceed);
    sum += m.log_likelihood;
    if (sum <= must_exceed) return sum;
  }
  return sum;
}

}  // namespace

Eigen::Vector3d refinePose(const Eigen::Vector3d& converged, const Eigen::Vector3d& odom_now, const std::vector<RefinementScan>& scans,
                           const RoomIndex& every_face, const ParticleFilterConfig& model, const PoseRefinementConfig& r) {
  if (scans.empty() || !converged.allFinite() || r.grid_step_m <= 0.0) return converged;
  // Every pose scored lies within search_m of `converged`, and nearly always within a few
  // degrees of its heading: each scan's faces found once for all of them.
  const std::vector<FaceShortlist> shortlists = windowShortlists(converged, odom_now, scans, every_face, model, r);
  // A pose is taken only when it scores above the best so far (by 1e-9): its score need not be
  // summed to the end once it cannot (windowScore's must_exceed), and the search is the same.
  const auto score = [&](const Eigen::Vector3d& pose, double must_exceed) {
    return windowScore(pose, odom_now, scans, every_face, model, r.opening_margin_m, shortlists, must_exceed);
  };
  // The grid's cells from the centre out: of poses that fit alike, the nearest stays.
  const std::vector<Eigen::Vector2d> offsets = gridOffsets(r);
  Eigen::Vector3d best = converged;
  double best_score = score(converged, -std::numeric_limits<double>::infinity());
  for (const auto& o : offsets) {
    const Eigen::Vector3d pose(converged.x() + o.x(), converged.y() + o.y(), converged.z());
    const double s = score(pose, best_score + 1e-9);
    if (s > best_score + 1e-9) best = pose, best_score = s;
  }
  // Then x, y and yaw, halving the steps (the association is discrete: no useful gradient).
  double step_m = 0.5 * r.grid_step_m, step_rad = 0.5 * M_PI / 180.0;
  for (int level = 0; level < 4; ++level, step_m *= 0.5, step_rad *= 0.5)
    for (bool improved = true; improved;) {
      improved = false;
      for (const Eigen::Vector3d& d : {Eigen::Vector3d(step_m, 0, 0), Eigen::Vector3d(-step_m, 0, 0), Eigen::Vector3d(0, step_m, 0),
                                       Eigen::Vector3d(0, -step_m, 0), Eigen::Vector3d(0, 0, step_rad), Eigen::Vector3d(0, 0, -step_rad)}) {
        Eigen::Vector3d pose = best + d;
        pose.z() = wrapAngle(pose.z());
        if ((pose.head<2>() - converged.head<2>()).norm() > r.search_m) continue;
        const double s = score(pose, best_score + 1e-9);
        if (s > best_score + 1e-9) best = pose, best_score = s, improved = true;
      }
    }
  return best;
}

}  // namespace bimloc::pf::detail
