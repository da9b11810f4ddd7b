// Where to look next (issue 28 §4): while the path still fits several places, a goal near the
// robot from which those places would be seen to differ most. Each place is a transform
// map <- odom, so one motion of the base (in its own frame now, hence in the odom frame) takes
// the robot to a different map pose in each place; from each of those the plan predicts a 2D
// range scan, and the motion whose scans differ most, reachable in every place, is the goal.
//
//   guide::GoalPlanner planner(storey, config.guide);
//   auto goal = planner.suggest(places, T_odom_base_now);   // nothing with fewer than 2 places
//   if (goal) walk_to(goal->T_odom_goal);                    // the odom frame: valid as it moves
#pragma once

#include <bimloc/bim/building.hpp>
#include <bimloc/geometry/planar_pose.hpp>

#include <memory>
#include <optional>
#include <vector>

namespace bimloc::guide {

struct GuideConfig {
  bool enabled = true;  // Localizer: suggest goals while searching (costs a planning every few seconds)
  // Candidate goals: rings around the robot, from min to max radius, each with `bearings` goals.
  double goal_min_m = 1.0;
  double goal_max_m = 6.0;
  int goal_rings = 6;
  // A goal must be walkable within this in every place: through doors, round walls (the
  // body's clearance kept), from a room into a room.
  double goal_walk_max_m = 10.0;
  int goal_bearings = 16;
  // The predicted scan: a 2D slice of the plan's wall faces at this height above the walls'
  // base (below window sills: only doors are gaps, as they are to the walking base too).
  int scan_rays = 90;
  double scan_range_m = 10.0;
  double scan_height_m = 0.6;
  // What tells two places apart is what the localizer's path evidence counts: distinct walls
  // (pf: FaceMargin, free space), each at most one face's worth, and it decides at
  // evidence_faces (2) of them. A wall counts when at least support_rays rays of the two
  // predicted scans differ on it by more than gate_sigmas range sigmas (plan versus site and a
  // place's own pose error, far above the lidar's 8 mm); the wall is the nearer of the two the
  // ray hits: the one seen in one place where the other has free space or a wall beyond.
  double range_sigma_m = 0.15;
  double gate_sigmas = 3.0;
  int support_rays = 3;
  double faces_to_decide = 2.0;
  // The body: goals and the walk to them keep this far from every wall in every place.
  double clearance_m = 0.4;
  // Information is in [0, 1]: the mean, over pairs of places, of the walls that tell them apart
  // over faces_to_decide, at most 1. Each metre of walk costs this much of it.
  double travel_cost_per_m = 0.02;
  // Below this much information, no goal: no candidate is predicted to decide (the faces apart
  // reach faces_to_decide for every pair). A goal that only helps had the base dither inside
  // look-alike offices where the tour would have left them (site_office 8 -> 9 of 11; 45
  // generated starts 24 -> 36 of 45, docs/results/2026-11-26-session14.md).
  double min_information = 0.99;
  // Localizer: plan again after this long, when the goal was reached (within goal_reached_m),
  // or when the places change.
  double replan_interval_s = 5.0;
  double goal_reached_m = 0.5;
  // Localizer: the places listed while searching (each fitted within itself, the filter's
  // fitPlaces) and the goal planned for them are refreshed at most this often, at the first
  // weighing this long after the last refresh; in between, the places kept move with the
  // odometry. They are advice (where the base might walk, what is left to tell apart): the
  // decision is the path evidence's and is weighed at every weighing all the same. At 10 Hz
  // scans and a weighing every 0.2 m, fitting every place and planning a goal at every weighing
  // cost a quarter of the search on a 100-room floor (docs/results/2026-11-27-h28speed6.md).
  // 0: at every weighing.
  double places_interval_s = 1.0;
};

// A place the path still fits: the base's map pose now, and the evidence margin of the best
// place over it (0 for the best itself).
struct Place {
  PlanarPose T_map_base = PlanarPose::Zero();
  double margin = 0;
};

struct LookGoal {
  PlanarPose motion = PlanarPose::Zero();       // the goal in the base frame now (same for every place)
  PlanarPose T_odom_goal = PlanarPose::Zero();  // the goal in the odom frame: stays valid as the base moves
  std::vector<PlanarPose> T_map_goal;           // the goal in the map, for each place (in places' order)
  double information = 0;                       // expected information gain at the goal, 0..1
  double distance_m = 0;                        // straight line from the base now
  double walk_m = 0;                            // the walk there, the longest over the places
};

class GoalPlanner {
 public:
  // The storey must outlive the planner: its wall faces are sliced once, here.
  GoalPlanner(const bim::Storey& storey, const GuideConfig& config);
  ~GoalPlanner();
  GoalPlanner(GoalPlanner&&) noexcept;

  // The goal, or nothing with fewer than two places, or when no candidate within reach is free
  // in every place and tells them apart by at least config.min_information.
  std::optional<LookGoal> suggest(const std::vector<Place>& places, const PlanarPose& T_odom_base) const;
  // The predicted scan from a map pose: range per ray (ray k at yaw + 2 pi k / scan_rays),
  // scan_range_m where it hits nothing. For tests and pictures.
  std::vector<double> predictScan(const PlanarPose& T_map_base) const;
  // Whether the body walks from `from` to `to` (map frame) as a goal must be walked: with its
  // clearance, through doors, within goal_walk_max_m, from a room into a room.
  bool reachable(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const;
  // The information (0..1) of scans from these map poses, one per place.
  double information(const std::vector<PlanarPose>& T_map_bases) const;
  // The information of one motion of the base (its frame now) for these places; nothing where
  // the goal is out of reach (reachable() is false) in one of them.
  std::optional<double> informationOf(const std::vector<Place>& places, const PlanarPose& motion) const;
  const GuideConfig& config() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bimloc::guide
