#include "loss_monitor.hpp"

#include "plan_view.hpp"
#include "window_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace bimloc::sgraph::detail {
namespace {

// A plan face counts as in view within this range, when at least kClearViewMinM of it is
// clear: a small room's walls and the far side of a corridor, where a 16-beam lidar's rings
// give the plane extraction points enough (farther, a wall is more often hidden by clutter
// the plan does not hold than missed by the extraction).
constexpr double kClearViewRangeM = 5.0;
constexpr double kClearViewMinM = 1.0;
// Farther than this from the height the base stood at on the storey's floor (two risers), it
// is on a flight: the storey's walls are not where the floor's view puts them (going down,
// the lidar is under the floor and sees the stairwell below), and the class rule is not asked.
constexpr double kOffFloorM = 0.3;

}  // namespace

std::string keyframeDoubt(const Graph& g, const Keyframe& kf, const std::vector<ScanObservation>& observed, bool solve_usable,
                          const SGraphConfig& c) {
  char text[200];
  if (!solve_usable) return "the optimization failed";
  if (kf.plan_walls < c.min_plan_associations) return std::to_string(kf.plan_walls) + " plan walls matched";
  // Walls matched to the plan against what contradicts the plan, per class: a robot metres off
  // along a corridor still matches the corridor's walls, but not the walls across it, which it
  // then sees either behind a plan wall or in the open, before a plan wall it does not see.
  // What contradicts the plan, from the keyframe's pose:
  //  - a plane matched to no plan wall, seen behind a solid plan face (the plan says the lidar
  //    cannot see there);
  //  - a plan face in clear view (PlanView: no other plan face and no plane the scan saw in
  //    between, not at a grazing angle, within kClearViewRangeM) in whose plane the scan has no
  //    plane. A wall seen in the open, hiding the plan's wall behind it, is as consistent
  //    with the plan as a cupboard before it: neither counts.
  // Not a contradiction: a plane in the open before the walls. The site holds every physical
  // element, the plan only its walls: furniture, stacked material, columns, stair sides. In
  // small rooms they outnumber the walls in view (the Duplex's: 3 and 5 such planes against 2
  // and 3 walls, lost after 5 such keyframes in a row while 0.002-0.03 m off;
  // docs/results/2026-11-27-h31tours2.md, section 3).
  // Nor a plane in the plane of a plan wall's face (within the association gate in angle and
  // offset), beyond the face's ends: some element the plan's walls do not cover (Jesse.1
  // level 0), agreeing with the plan along the normal it constrains.
  const double gate = std::sqrt(c.association_gate_mahalanobis2);
  const double cos_tol = std::cos(gate * c.association_sigma_azimuth_deg * M_PI / 180.0), d_tol = gate * c.association_sigma_d_m;
  const auto inFacePlane = [&](const ScanObservation& o, const WallNode& node, int f) {
    return node.normal(f).dot(o.normal_map) > cos_tol && std::abs(node.normal(f).dot(o.centroid_map) + node.d(f)) < d_tol;
  };
  const auto inPlanPlane = [&](const ScanObservation& o) {
    for (const auto& node : g.nodes) {
      if (node.kind != WallNode::Kind::Plan || !node.active) continue;
      for (int f = 0; f < 2; ++f)
        if (inFacePlane(o, node, f)) return true;
    }
    return false;
  };
  const bool on_floor = !g.floor_base_z || std::abs(kf.z_map - *g.floor_base_z) < kOffFloorM;
  const PlanView view(g, kf.planar().head<2>(), on_floor ? kClearViewRangeM : 0.0);
  std::array<int, 2> matched{}, behind{}, unseen{};
  for (const auto& o : observed) {
    if (!on_floor) break;
    bool on_plan_wall = false;  // matched to a plan wall (a match to a new plane does not count)
    for (const auto& p : kf.planes)
      on_plan_wall = on_plan_wall || (p.observation == o.index && g.nodes[static_cast<std::size_t>(p.node)].kind == WallNode::Kind::Plan);
    if (!on_plan_wall && !inPlanPlane(o) && view.blocked(o.centroid_map, d_tol)) ++behind[o.axis == bim::WallAxis::X ? 0 : 1];
  }
  for (const auto& p : kf.planes) {
    const auto& node = g.nodes[static_cast<std::size_t>(p.node)];
    if (node.kind == WallNode::Kind::Plan) ++matched[node.axis(p.face) == bim::WallAxis::X ? 0 : 1];
  }
  // Seen: some plane of the scan in the face's plane, matched or not (a wall split in the plan
  // into segments in line is one plane, matched to one of them).
  std::vector<PlanView::Occluder> occluders;
  for (const auto& o : observed) {
    const Eigen::Vector2d along(-o.normal_map.y(), o.normal_map.x());
    occluders.push_back({o.centroid_map - 0.5 * o.extent_m * along, o.centroid_map + 0.5 * o.extent_m * along});
  }
  for (const PlanFaceRef& r : view.facesInClearView(kClearViewMinM, occluders)) {
    const WallNode& node = g.nodes[static_cast<std::size_t>(r.node)];
    const bool seen = std::any_of(observed.begin(), observed.end(), [&](const ScanObservation& o) { return inFacePlane(o, node, r.face); });
    if (!seen) ++unseen[node.axis(r.face) == bim::WallAxis::X ? 0 : 1];
  }
  for (int k = 0; k < 2; ++k) {
    const int against = behind[k] + unseen[k];
    if (matched[k] < c.min_plan_fraction * (matched[k] + against)) {
      std::snprintf(text, sizeof text, "%d of %d %s walls matched the plan (%d planes behind a plan wall, %d plan walls in view unseen)",
                    matched[k], matched[k] + against, k == 0 ? "x" : "y", behind[k], unseen[k]);
      return text;
    }
  }
  // The planes that disagree with the optimized keyframe: one wall built off its plan or one
  // wrong association (both held by the robust kernels) is not a lost robot; most of them is.
  const std::vector<double> residuals2 = planeResiduals2(g, kf);
  const auto disagree = std::count_if(residuals2.begin(), residuals2.end(), [&](double r2) { return r2 > c.loss_mahalanobis2; });
  if (!residuals2.empty() && 2 * disagree > static_cast<long>(residuals2.size())) {
    std::snprintf(text, sizeof text, "%ld of %zu planes disagree after the optimization", static_cast<long>(disagree), residuals2.size());
    return text;
  }
  const double correction = (kf.planar() - kf.predicted).head<2>().norm();
  if (correction > c.loss_correction_m) {
    std::snprintf(text, sizeof text, "moved %.2f m from its odometry prediction", correction);
    return text;
  }
  return "";
}

TrackingState LossMonitor::update(const std::string& doubt, std::vector<std::string>& warnings) {
  if (doubt.empty()) ++good_streak_, bad_streak_ = 0;
  else ++bad_streak_, good_streak_ = 0;
  if (state_ == TrackingState::Tracking && bad_streak_ >= config_.lost_after_keyframes) {
    state_ = TrackingState::Lost;
    warnings.push_back("lost: " + std::to_string(bad_streak_) + " bad keyframes in a row (last: " + doubt + ")");
  } else if (state_ == TrackingState::Lost && good_streak_ >= config_.recover_after_keyframes) {
    state_ = TrackingState::Tracking;
    warnings.push_back("tracking again after " + std::to_string(good_streak_) + " good keyframes");
  }
  return state_;
}

}  // namespace bimloc::sgraph::detail
