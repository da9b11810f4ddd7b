#include "loss_monitor.hpp"

#include "window_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace bimloc::sgraph::detail {

std::string keyframeDoubt(const Graph& g, const Keyframe& kf, const std::vector<ScanObservation>& observed, bool solve_usable,
                          const SGraphConfig& c) {
  char text[160];
  if (!solve_usable) return "the optimization failed";
  if (kf.plan_walls < c.min_plan_associations) return std::to_string(kf.plan_walls) + " plan walls matched";
  // Walls seen and walls matched to the plan, per class: a robot metres off along a corridor
  // still matches the corridor's walls, but not the walls across it.
  // A plane not matched to a plan wall that lies in the plane of a plan wall's face (within the
  // association gate in angle and offset), beyond the face's ends, is some element the plan's
  // walls do not cover (Jesse.1 level 0: planes in line with a wall, 1-9 cm off its plane, which
  // the graph then keeps as new planes): it agrees with the plan along the normal it
  // constrains, so it can neither confirm nor contradict the track. A robot metres off along a
  // corridor sees the walls across it metres off every plan plane: those still count.
  const double gate = std::sqrt(c.association_gate_mahalanobis2);
  const double cos_tol = std::cos(gate * c.association_sigma_azimuth_deg * M_PI / 180.0), d_tol = gate * c.association_sigma_d_m;
  const auto inPlanPlane = [&](const ScanObservation& o) {
    for (const auto& node : g.nodes) {
      if (node.kind != WallNode::Kind::Plan || !node.active) continue;
      for (int f = 0; f < 2; ++f)
        if (node.normal(f).dot(o.normal_map) > cos_tol && std::abs(node.normal(f).dot(o.centroid_map) + node.d(f)) < d_tol) return true;
    }
    return false;
  };
  std::array<int, 2> seen{}, matched{};
  for (const auto& o : observed) {
    bool on_plan_wall = false;  // matched to a plan wall (a match to a new plane does not count)
    for (const auto& p : kf.planes)
      on_plan_wall = on_plan_wall || (p.observation == o.index && g.nodes[static_cast<std::size_t>(p.node)].kind == WallNode::Kind::Plan);
    if (on_plan_wall || !inPlanPlane(o)) ++seen[o.axis == bim::WallAxis::X ? 0 : 1];
  }
  for (const auto& p : kf.planes) {
    const auto& node = g.nodes[static_cast<std::size_t>(p.node)];
    if (node.kind == WallNode::Kind::Plan) ++matched[node.axis(p.face) == bim::WallAxis::X ? 0 : 1];
  }
  for (int k = 0; k < 2; ++k)
    if (matched[k] < c.min_plan_fraction * seen[k])
      return std::to_string(matched[k]) + " of " + std::to_string(seen[k]) + (k == 0 ? " x" : " y") + " walls matched the plan";
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
