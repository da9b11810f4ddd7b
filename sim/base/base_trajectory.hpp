// The simulated legged base: a kinematic Spot-like body that follows a motion script within
// speed, turn-rate and acceleration limits, with gait-induced body motion. Ground truth at
// any instant. Bullet keeps the script honest when it is planned.
#pragma once

#include "sim/base/motion_config.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace bimloc::sim {

class World;

// A motion the body cannot make. `where` tells the scenario loader which line to blame:
// the start (the body does not fit there), segment `segment` (1-based: the segment ending at
// the script's segment-th point, so for waypoints at waypoint number `segment`), or the script
// as a whole (an unknown room, no path to a room).
class MotionError : public std::runtime_error {
 public:
  enum class Where { Start, Segment, Script };
  MotionError(const std::string& message, Where where_, int segment_ = 0)
      : std::runtime_error(message), where(where_), segment(segment_) {}
  Where where;
  int segment;
};

struct Pose2 {
  double x = 0.0, y = 0.0, yaw = 0.0;  // map frame, metres and radians
};

class BaseTrajectory {
 public:
  // Plans the motion from `start` on `storey`: expands the script (waypoints, a tour through
  // rooms and their doors, over the stairs to rooms on other storeys, a random walk in a room)
  // into a path, checks every segment with a
  // Bullet sweep of the body, and times it under the limits. Throws MotionError (a
  // std::runtime_error) naming the segment and the contact point for a path through a wall.
  static BaseTrajectory plan(const World& world, std::size_t storey, const Pose2& start, const MotionConfig& motion,
                             double duration_s, std::uint64_t seed);

  double duration_s() const;
  // When the script itself ends: the base stands still from then on. May be later than
  // duration_s() (a tour cut short), which the caller may want to report.
  double script_duration_s() const;
  // Ground truth map -> base_link at time t (clamped to [0, duration]): planar motion, the
  // floor height under the body, and the gait's bob, roll and pitch.
  Eigen::Isometry3d T_map_base(double t_s) const;
  // The planar path (x, y, yaw) at its corners, for drawing and tests: the start pose, then
  // every corner with the heading the base arrives with (it then turns in place).
  const std::vector<Pose2>& corners() const;
  // Height of the floor under the body at time t (map z); on a flight, the run line's.
  double floor_z(double t_s) const;
  // The storey the base is on at time t (issue 31): the one it came from while on a flight,
  // the new one from the instant it steps off. And whether it is on a flight.
  std::size_t storey(double t_s) const;
  bool onStairs(double t_s) const;
  // The storeys it stands on, in the order it reaches them (the start storey first): more
  // than one when the script climbs.
  const std::vector<std::size_t>& storeys() const;
  bool multiStorey() const { return storeys().size() > 1; }
  // Distance walked by time t (metres).
  double distance_m(double t_s) const;
  // The first moment at or after t when the base is at rest (the end of its turn or straight
  // move under way): where a new plan can take over without a jump in speed.
  double restAfter(double t_s) const;

  BaseTrajectory(BaseTrajectory&&) noexcept;
  BaseTrajectory& operator=(BaseTrajectory&&) noexcept;
  ~BaseTrajectory();

 private:
  struct Impl;
  explicit BaseTrajectory(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace bimloc::sim
