#include <bimloc/guide/look_goal.hpp>

#include "wall_slice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::guide {

struct GoalPlanner::Impl {
  const bim::Storey& storey;
  GuideConfig config;
  std::vector<detail::Segment2> walls;  // the slice at scan height, doors as gaps
  detail::RoomBoxes rooms;              // storey.roomAt's answer, without testing every room's outline

  // The scan from `pose` against `segments` (a subset of walls near it).
  std::vector<double> scan(const std::vector<detail::Segment2>& segments, const PlanarPose& pose) const {
    const int n = std::max(1, config.scan_rays);
    std::vector<double> ranges(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      const double a = pose.z() + 2.0 * M_PI * k / n;
      ranges[static_cast<std::size_t>(k)] =
          detail::castRay(segments, pose.head<2>(), Eigen::Vector2d(std::cos(a), std::sin(a)), config.scan_range_m);
    }
    return ranges;
  }

  // The mean over pairs of places of 1 - exp(-D), D the scans' expected log-likelihood ratio:
  // per ray the KL divergence of two Gaussian ranges (equal sigma), capped where clutter
  // explains either range, scaled to the scan's independent rays.
  double information(const std::vector<std::vector<double>>& scans) const {
    const double cap = -std::log(std::clamp(config.clutter_probability, 1e-6, 1.0));
    const double inv = 1.0 / (2.0 * config.range_sigma_m * config.range_sigma_m);
    double sum = 0;
    int pairs = 0;
    for (std::size_t i = 0; i < scans.size(); ++i)
      for (std::size_t j = i + 1; j < scans.size(); ++j) {
        double d = 0;
        for (std::size_t k = 0; k < scans[i].size(); ++k) {
          const double delta = scans[i][k] - scans[j][k];
          d += std::min(cap, delta * delta * inv);
        }
        d *= config.independent_rays / static_cast<double>(std::max<std::size_t>(1, scans[i].size()));
        sum += 1.0 - std::exp(-d);
        ++pairs;
      }
    return pairs ? sum / pairs : 0.0;
  }

  // The body fits at `to` and walks there straight from `from`; inside a room when `from` is.
  bool reachable(const std::vector<detail::Segment2>& segments, const Eigen::Vector2d& from, const Eigen::Vector2d& to) const {
    const Eigen::Vector2d step = to - from;
    const double length = step.norm();
    if (!(length > 1e-9)) return true;
    // The walk is checked from a body's width out: a place that puts the robot nearer a wall
    // than the clearance (a rival's pose is only as good as its fit) may still walk away.
    const Eigen::Vector2d start = from + std::min(config.clearance_m, 0.5 * length) / length * step;
    for (const auto& s : segments)
      if (detail::distanceTo(s, to) < config.clearance_m) return false;
    if (!detail::walkClear(segments, start, to, config.clearance_m)) return false;
    // the part skipped may not pass through a wall either
    if (!detail::walkClear(segments, from, start, 0.0)) return false;
    return !rooms.inAnyRoom(from) || rooms.inAnyRoom(to);
  }
};

GoalPlanner::GoalPlanner(const bim::Storey& storey, const GuideConfig& config)
    : impl_(std::make_unique<Impl>(Impl{storey, config, detail::sliceWalls(storey, config.scan_height_m), detail::RoomBoxes(storey)})) {}
GoalPlanner::~GoalPlanner() = default;
GoalPlanner::GoalPlanner(GoalPlanner&&) noexcept = default;
const GuideConfig& GoalPlanner::config() const { return impl_->config; }

std::vector<double> GoalPlanner::predictScan(const PlanarPose& T_map_base) const {
  return impl_->scan(detail::segmentsNear(impl_->walls, T_map_base.head<2>(), impl_->config.scan_range_m), T_map_base);
}

bool GoalPlanner::reachable(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const {
  return impl_->reachable(impl_->walls, from, to);
}

double GoalPlanner::information(const std::vector<PlanarPose>& T_map_bases) const {
  std::vector<std::vector<double>> scans;
  for (const auto& p : T_map_bases) scans.push_back(predictScan(p));
  return impl_->information(scans);
}

std::optional<LookGoal> GoalPlanner::suggest(const std::vector<Place>& places, const PlanarPose& T_odom_base) const {
  const Impl& m = *impl_;
  const GuideConfig& c = m.config;
  if (places.size() < 2 || c.goal_rings < 1 || c.goal_bearings < 1) return std::nullopt;
  // Each place's walls within reach of any of its goals' scans: culled once.
  std::vector<std::vector<detail::Segment2>> near;
  for (const auto& p : places)
    near.push_back(detail::segmentsNear(m.walls, p.T_map_base.head<2>(), c.goal_max_m + c.scan_range_m));
  std::optional<LookGoal> best;
  double best_score = -std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> scans(places.size());
  std::vector<PlanarPose> there(places.size());
  for (int ring = 0; ring < c.goal_rings; ++ring) {
    const double radius = c.goal_rings == 1 ? c.goal_max_m
                                            : c.goal_min_m + (c.goal_max_m - c.goal_min_m) * ring / (c.goal_rings - 1);
    for (int b = 0; b < c.goal_bearings; ++b) {
      const double bearing = 2.0 * M_PI * b / c.goal_bearings;
      // Facing the way it walked: the scan is all round, so the heading only says how it got there.
      const PlanarPose motion(radius * std::cos(bearing), radius * std::sin(bearing), wrapAngle(bearing));
      bool free = true;
      for (std::size_t i = 0; i < places.size() && free; ++i) {
        there[i] = compose(places[i].T_map_base, motion);
        free = m.reachable(near[i], places[i].T_map_base.head<2>(), there[i].head<2>());
      }
      if (!free) continue;
      for (std::size_t i = 0; i < places.size(); ++i) scans[i] = m.scan(near[i], there[i]);
      const double info = m.information(scans);
      const double score = info - c.travel_cost_per_m * radius;
      if (info < c.min_information || score <= best_score) continue;
      best_score = score;
      LookGoal g;
      g.motion = motion;
      g.T_odom_goal = compose(T_odom_base, motion);
      g.T_map_goal = there;
      g.information = info;
      g.distance_m = radius;
      best = std::move(g);
    }
  }
  return best;
}

}  // namespace bimloc::guide
