#include "plan_view.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sgraph::detail {
namespace {

// A line of sight within this of a face's end passes round it (the wall's corner, its
// thickness, the face's extent rounded in the plan).
constexpr double kPlanViewEndMarginM = 0.15;
// Samples along a face, for how much of it is in clear view.
constexpr double kPlanViewSampleM = 0.25;
// Seen at more than this from its normal, a face gives the plane extraction too few points in
// a scan of a 16-beam lidar (its rings cross it at a slant): not counted as in clear view.
constexpr double kPlanViewMaxIncidenceDeg = 70.0;

bool inOpening(const WallNode& node, int f, double along) {
  for (const auto& o : node.openings[static_cast<std::size_t>(f)])
    if (along >= o.along_min_m && along <= o.along_max_m) return true;  // any height: the lidar's rings see through it
  return false;
}

}  // namespace

PlanView::PlanView(const Graph& g, const Eigen::Vector2d& from, double range_m) : g_(g), from_(from), range_m_(range_m) {
  for (std::size_t n = 0; n < g.nodes.size(); ++n) {
    const WallNode& node = g.nodes[n];
    if (node.kind != WallNode::Kind::Plan || !node.active) continue;
    for (int f = 0; f < node.faces; ++f) {
      const auto k = static_cast<std::size_t>(f);
      if (bim::distanceToSegment(from, node.start[k], node.end[k]) <= range_m) near_.push_back({static_cast<int>(n), f});
    }
  }
}

bool PlanView::blocked(const Eigen::Vector2d& to, double behind_m, int skip_node) const {
  for (const PlanFaceRef& r : near_) {
    if (r.node == skip_node) continue;
    const WallNode& node = g_.nodes[static_cast<std::size_t>(r.node)];
    const Eigen::Vector2d n = node.normal(r.face);
    const double d = node.d(r.face);
    const double dp = n.dot(from_) + d, dq = n.dot(to) + d;
    if (!(dp > 0) || !(dq < -behind_m)) continue;  // seen from the front, the point behind it
    const Eigen::Vector2d x = from_ + (dp / (dp - dq)) * (to - from_);
    const double along = node.along(r.face, x);
    if (along < kPlanViewEndMarginM || along > node.length(r.face) - kPlanViewEndMarginM) continue;
    if (inOpening(node, r.face, along)) continue;
    return true;
  }
  return false;
}

std::vector<PlanFaceRef> PlanView::facesInClearView(double min_length_m, const std::vector<Occluder>& occluders) const {
  const double cos_max = std::cos(kPlanViewMaxIncidenceDeg * M_PI / 180.0);
  std::vector<PlanFaceRef> out;
  for (const PlanFaceRef& r : near_) {
    const WallNode& node = g_.nodes[static_cast<std::size_t>(r.node)];
    if (node.buried[static_cast<std::size_t>(r.face)]) continue;  // inside another wall's body
    const Eigen::Vector2d n = node.normal(r.face);
    if (!(n.dot(from_) + node.d(r.face) > 0)) continue;  // looks away
    const Eigen::Vector2d a = node.start[static_cast<std::size_t>(r.face)];
    const double length = node.length(r.face);
    if (!(length > 2 * kPlanViewEndMarginM)) continue;
    const Eigen::Vector2d u = (node.end[static_cast<std::size_t>(r.face)] - a) / length;
    double clear = 0;
    for (double s = kPlanViewEndMarginM; s <= length - kPlanViewEndMarginM && clear < min_length_m; s += kPlanViewSampleM) {
      if (inOpening(node, r.face, s)) continue;
      const Eigen::Vector2d p = a + s * u;
      const Eigen::Vector2d ray = p - from_;
      const double range = ray.norm();
      if (!(range > 1e-6) || range > range_m_ || -ray.dot(n) / range < cos_max) continue;
      // Another plan face in between hides it (the point itself lies on this face: skip its node),
      // or something the scan saw.
      if (blocked(p, 0.01, r.node)) continue;
      bool hidden = false;
      for (const Occluder& o : occluders) hidden = hidden || bim::segmentsCross(from_, p, o.a, o.b);
      if (!hidden) clear += kPlanViewSampleM;
    }
    if (clear >= min_length_m) out.push_back(r);
  }
  return out;
}

}  // namespace bimloc::sgraph::detail
