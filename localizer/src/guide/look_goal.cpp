#include <bimloc/guide/look_goal.hpp>

#include "ray_fan.hpp"
#include "walk_grid.hpp"
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
  detail::WalkGrid grid;                // where the body fits, for walking distances
  detail::SegmentGrid near_walls;       // `walls` near a point, through a grid

  // The walk from a place to `to`: its length, or infinity where the body cannot get there
  // (not free, beyond goal_walk_max_m, or out of every room from a room).
  double walk(const detail::WalkGrid::Distances& from_place, const Eigen::Vector2d& from, const Eigen::Vector2d& to) const {
    const double metres = grid.distance(from_place, to);
    if (!std::isfinite(metres)) return metres;
    return !rooms.inAnyRoom(from) || rooms.inAnyRoom(to) ? metres : std::numeric_limits<double>::infinity();
  }

  // The walk from `from` to `to` (its own walking distances): as walk() with them.
  double walkFrom(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const {
    const double metres = grid.distanceBetween(from, to, config.goal_walk_max_m);
    if (!std::isfinite(metres)) return metres;
    return !rooms.inAnyRoom(from) || rooms.inAnyRoom(to) ? metres : std::numeric_limits<double>::infinity();
  }

  // The scan from `pose` against `segments` (a subset of walls near it): per ray its range and
  // the wall it ends on (-1: none within range).
  struct Scan {
    std::vector<double> ranges;
    std::vector<int> walls;
  };
  Scan scan(const std::vector<detail::Segment2>& segments, const PlanarPose& pose) const {
    const int n = std::max(1, config.scan_rays);
    Scan out;
    out.ranges.resize(static_cast<std::size_t>(n));
    out.walls.resize(static_cast<std::size_t>(n));
    // Each ray is cast against the segments it can meet (detail::RayFan), in their order: the same
    // first hit as against them all.
    const detail::RayFan fan(segments, pose.head<2>(), pose.z(), n, config.scan_range_m);
    for (int k = 0; k < n; ++k) {
      const double a = pose.z() + 2.0 * M_PI * k / n;
      const auto i = static_cast<std::size_t>(k);
      out.ranges[i] = fan.cast(k, pose.head<2>(), Eigen::Vector2d(std::cos(a), std::sin(a)), config.scan_range_m, &out.walls[i]);
    }
    return out;
  }
  // The same against the walls within the scan's range of the pose.
  Scan scanAt(const PlanarPose& pose) const { return scan(near_walls.near(pose.head<2>(), config.scan_range_m), pose); }

  // The walls that tell two predicted scans apart, as the path evidence counts them (GuideConfig):
  // per wall (the nearer of the two a ray ends on), the rays that differ beyond the gate; a wall
  // counts once support_rays of them do.
  int wallsApart(const Scan& a, const Scan& b) const {
    std::vector<int> walls;
    const double gate = config.gate_sigmas * config.range_sigma_m;
    for (std::size_t k = 0; k < a.ranges.size() && k < b.ranges.size(); ++k) {
      if (std::abs(a.ranges[k] - b.ranges[k]) <= gate) continue;
      const int wall = a.ranges[k] < b.ranges[k] ? a.walls[k] : b.walls[k];
      if (wall >= 0) walls.push_back(wall);
    }
    std::sort(walls.begin(), walls.end());
    int apart = 0;
    for (std::size_t i = 0; i < walls.size();) {
      std::size_t j = i;
      while (j < walls.size() && walls[j] == walls[i]) ++j;
      apart += static_cast<int>(j - i) >= config.support_rays ? 1 : 0;
      i = j;
    }
    return apart;
  }

  // The mean over pairs of places of min(1, walls apart / faces_to_decide).
  double information(const std::vector<Scan>& scans) const {
    double sum = 0;
    int pairs = 0;
    for (std::size_t i = 0; i < scans.size(); ++i)
      for (std::size_t j = i + 1; j < scans.size(); ++j) {
        sum += std::min(1.0, wallsApart(scans[i], scans[j]) / std::max(1e-9, config.faces_to_decide));
        ++pairs;
      }
    return pairs ? sum / pairs : 0.0;
  }
};

GoalPlanner::GoalPlanner(const bim::Storey& storey, const GuideConfig& config)
    : impl_(std::make_unique<Impl>(
          Impl{storey, config, detail::sliceWalls(storey, config.scan_height_m), detail::RoomBoxes(storey), detail::WalkGrid({}, 0.0), detail::SegmentGrid()})) {
  impl_->grid = detail::WalkGrid(impl_->walls, config.clearance_m);
  impl_->near_walls = detail::SegmentGrid(impl_->walls);
}
GoalPlanner::~GoalPlanner() = default;
GoalPlanner::GoalPlanner(GoalPlanner&&) noexcept = default;
const GuideConfig& GoalPlanner::config() const { return impl_->config; }

std::vector<double> GoalPlanner::predictScan(const PlanarPose& T_map_base) const {
  return impl_->scanAt(T_map_base).ranges;
}

bool GoalPlanner::reachable(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const {
  return std::isfinite(impl_->walkFrom(from, to));
}

double GoalPlanner::information(const std::vector<PlanarPose>& T_map_bases) const {
  std::vector<Impl::Scan> scans;
  for (const auto& p : T_map_bases) scans.push_back(impl_->scanAt(p));
  return impl_->information(scans);
}

std::optional<double> GoalPlanner::informationOf(const std::vector<Place>& places, const PlanarPose& motion) const {
  const Impl& m = *impl_;
  std::vector<Impl::Scan> scans;
  for (const auto& p : places) {
    const PlanarPose there = compose(p.T_map_base, motion);
    if (!std::isfinite(m.walkFrom(p.T_map_base.head<2>(), there.head<2>()))) return std::nullopt;
    scans.push_back(m.scanAt(there));
  }
  return m.information(scans);
}

std::optional<LookGoal> GoalPlanner::suggest(const std::vector<Place>& places, const PlanarPose& T_odom_base) const {
  const Impl& m = *impl_;
  const GuideConfig& c = m.config;
  if (places.size() < 2 || c.goal_rings < 1 || c.goal_bearings < 1) return std::nullopt;
  // The trial goals: motions on rings around the base. Facing the way it walked: the scan is
  // all round, so the heading only says how it got there.
  struct Trial {
    double radius;
    PlanarPose motion;
  };
  std::vector<Trial> trials;
  for (int ring = 0; ring < c.goal_rings; ++ring) {
    const double radius = c.goal_rings == 1 ? c.goal_max_m
                                            : c.goal_min_m + (c.goal_max_m - c.goal_min_m) * ring / (c.goal_rings - 1);
    for (int b = 0; b < c.goal_bearings; ++b) {
      const double bearing = 2.0 * M_PI * b / c.goal_bearings;
      trials.push_back({radius, PlanarPose(radius * std::cos(bearing), radius * std::sin(bearing), wrapAngle(bearing))});
    }
  }
  // Each place's walls within reach of any of its goals' scans, and its walking distances to
  // its goals: once.
  std::vector<std::vector<detail::Segment2>> near;
  std::vector<detail::WalkGrid::Distances> walks;
  std::vector<Eigen::Vector2d> goals;
  for (const auto& p : places) {
    near.push_back(m.near_walls.near(p.T_map_base.head<2>(), c.goal_max_m + c.scan_range_m));
    goals.clear();
    for (const auto& t : trials) goals.push_back(compose(p.T_map_base, t.motion).head<2>());
    walks.push_back(m.grid.from(p.T_map_base.head<2>(), goals, c.goal_walk_max_m));
  }
  std::optional<LookGoal> best;
  double best_score = -std::numeric_limits<double>::infinity();
  std::vector<Impl::Scan> scans(places.size());
  std::vector<PlanarPose> there(places.size());
  for (const auto& [radius, motion] : trials) {
    // Reachable in every place (through doors: the walking distance), and walked the longest of those.
    double walk_m = 0;
    for (std::size_t i = 0; i < places.size() && std::isfinite(walk_m); ++i) {
      there[i] = compose(places[i].T_map_base, motion);
      walk_m = std::max(walk_m, m.walk(walks[i], places[i].T_map_base.head<2>(), there[i].head<2>()));
    }
    if (!std::isfinite(walk_m)) continue;
    for (std::size_t i = 0; i < places.size(); ++i) scans[i] = m.scan(near[i], there[i]);
    const double info = m.information(scans);
    const double score = info - c.travel_cost_per_m * walk_m;
    if (info < c.min_information || score <= best_score) continue;
    best_score = score;
    LookGoal g;
    g.motion = motion;
    g.T_odom_goal = compose(T_odom_base, motion);
    g.T_map_goal = there;
    g.information = info;
    g.distance_m = radius;
    g.walk_m = walk_m;
    best = std::move(g);
  }
  return best;
}

}  // namespace bimloc::guide
