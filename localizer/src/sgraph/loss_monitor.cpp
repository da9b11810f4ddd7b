#include "loss_monitor.hpp"

#include "window_solver.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

namespace bimloc::sgraph::detail {

std::string keyframeDoubt(const Graph& g, const Keyframe& kf, const std::vector<ScanObservation>& observed, bool solve_usable,
                          const SGraphConfig& c) {
  char text[160];
  if (!solve_usable) return "the optimization failed";
  if (kf.plan_walls < c.min_plan_associations) return std::to_string(kf.plan_walls) + " plan walls matched";
  // Walls seen and walls matched to the plan, per class: a robot metres off along a corridor
  // still matches the corridor's walls, but not the walls across it.
  std::array<int, 2> seen{}, matched{};
  for (const auto& o : observed) ++seen[o.axis == bim::WallAxis::X ? 0 : 1];
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
