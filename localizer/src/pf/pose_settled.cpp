#include "pose_settled.hpp"

#include "path_evidence.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <limits>

namespace bimloc::pf::detail {
namespace {

// Each scan's matches with the base at `pose_now`, as the refinement scores them.
std::vector<std::vector<ObservationMatch>> windowMatches(const Eigen::Vector3d& pose_now, const Eigen::Vector3d& odom_now,
                                                         const std::vector<RefinementScan>& scans, const RoomIndex& faces,
                                                         const ParticleFilterConfig& model, double opening_margin_m,
                                                         const std::vector<FaceShortlist>& shortlists) {
  const Eigen::Vector3d T_map_odom = compose(pose_now, inverse(odom_now));
  std::vector<std::vector<ObservationMatch>> out(scans.size());
  for (std::size_t k = 0; k < scans.size(); ++k)
    matchScanAt(T_map_odom, scans[k], faces, model, opening_margin_m, &out[k], &shortlists[k]);
  return out;
}

}  // namespace

LocalMargin localMargin(const Eigen::Vector3d& refined, const Eigen::Vector3d& odom_now, const std::vector<RefinementScan>& scans,
                        const RoomIndex& every_face, const ParticleFilterConfig& model, const PoseRefinementConfig& r, double min_m,
                        double enough) {
  LocalMargin result;
  result.margin = std::numeric_limits<double>::infinity();
  if (scans.empty() || r.grid_step_m <= 0.0 || !refined.allFinite()) return result;
  // The rivals: the refinement's grid, from min_m out to search_m, nearest first (the closest
  // poses are the likeliest to explain the window alike).
  const std::vector<Eigen::Vector2d> offsets = gridOffsets(r, min_m);
  // Every rival within search_m of `refined`, at its heading: each scan's faces found once.
  const std::vector<FaceShortlist> shortlists = windowShortlists(refined, odom_now, scans, every_face, model, r);
  const auto at_p = windowMatches(refined, odom_now, scans, every_face, model, r.opening_margin_m, shortlists);
  for (const auto& o : offsets) {
    const Eigen::Vector3d q(refined.x() + o.x(), refined.y() + o.y(), refined.z());
    const auto at_q = windowMatches(q, odom_now, scans, every_face, model, r.opening_margin_m, shortlists);
    FaceMargin margin;
    for (std::size_t k = 0; k < scans.size(); ++k)
      for (std::size_t m = 0; m < at_p[k].size() && m < at_q[k].size(); ++m) margin.add(at_p[k][m], at_q[k][m]);
    const double total = margin.total(model.gate_mahalanobis2, static_cast<double>(scans.size()));
    if (total < result.margin) {
      result.margin = total, result.rival = q;
      if (total < enough) break;
    }
  }
  return result;
}

}  // namespace bimloc::pf::detail
