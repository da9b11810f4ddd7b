// Timing of the planar motion: a table of phases (turn in place, straight move, hold), each a
// rest-to-rest trapezoidal velocity profile under the speed and acceleration limits. Looked up
// by binary search, evaluated in closed form: the lidar asks for a pose at every firing.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace bimloc::sim {

// Rest-to-rest motion over `length` (metres or radians): accelerate, cruise, decelerate; a
// triangle when the move is too short to reach v_max.
struct RestToRest {
  double length = 0.0, accel = 1.0, v_peak = 0.0, t_ramp = 0.0, t_cruise = 0.0;

  static RestToRest plan(double length, double v_max, double a_max);
  double duration() const { return 2.0 * t_ramp + t_cruise; }
  double position(double t) const;  // 0 .. length
  double speed(double t) const;      // >= 0
};

struct PlanarState {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  double yaw = 0.0;        // radians, continuous across turns (not wrapped)
  double speed = 0.0;      // m/s along the path
  double turn_rate = 0.0;  // rad/s
  double distance = 0.0;   // metres walked since t = 0
  double floor_z = 0.0;    // floor under the body (on a flight: the run line's height)
  // On a flight (issue 31): the slope of the run line along the direction of travel (positive
  // going up; the body pitches nose-up by it), and which storey the base is on: the storey it
  // came from until it steps off the flight.
  double slope_rad = 0.0;
  int storey = 0;
  bool on_stairs = false;
};

struct MotionLimits {
  double max_speed_mps = 0.8, max_accel_mps2 = 0.5;
  double max_turn_rate_rps = 1.0, max_turn_accel_rps2 = 2.0;
};

class Timeline {
 public:
  // floor_z(xy): the floor height under the body, sampled while the table is built.
  Timeline(const Eigen::Vector2d& start, double yaw, const MotionLimits& limits,
           std::function<double(const Eigen::Vector2d&)> floor_z, int storey = 0);
  Timeline() = default;

  void turnTo(double yaw);               // the shorter way round; nothing if already there
  void moveTo(const Eigen::Vector2d& p);  // straight, facing the direction of travel
  // Up or down a flight, straight to p (facing the direction of travel): the floor goes linearly
  // from where the base stands to z_end (the run line), at most max_speed_mps horizontally;
  // the base is on `storey_after` once it has stepped off.
  void climbTo(const Eigen::Vector2d& p, double z_end, double max_speed_mps, int storey_after);
  // A move on a landing or onto the new floor, its floor going linearly to z (the ends of a
  // flight and the floor beside them agree to a few millimetres), without asking the sampler
  // (which looks at one storey's mesh); not a flight: no slope.
  void moveFlatTo(const Eigen::Vector2d& p, double z);
  int storey() const { return storey_; }
  double floorHere() const { return floor_here_; }  // Planning done: forget the floor sampler, which refers to the world.
  void seal() { floor_z_ = nullptr; }
  double end_s() const { return phases_.empty() ? 0.0 : phases_.back().t1; }
  const Eigen::Vector2d& position() const { return position_; }
  double yaw() const { return yaw_; }
  PlanarState at(double t_s) const;  // holds the last state after end_s()
  // The first moment at or after t_s when the body is at rest: the end of the phase under way
  // (every phase is rest to rest), or t_s itself when none is.
  double restAfter(double t_s) const {
    const Phase* p = find(t_s);
    return p ? p->t1 : t_s;
  }

 private:
  struct Phase {
    bool move = false;  // else a turn
    double t0 = 0.0, t1 = 0.0;
    Eigen::Vector2d from = Eigen::Vector2d::Zero(), dir = Eigen::Vector2d::Zero();
    double yaw0 = 0.0, turn_sign = 0.0, distance0 = 0.0;
    RestToRest profile;
    std::vector<double> floor_z;  // along a move every kFloorStep_m (both ends included); else one
    double slope_rad = 0.0;       // a climb's slope (floor_z then holds its two ends)
    int storey = 0;
    bool stairs = false;
  };
  void addMove(const Eigen::Vector2d& target, std::vector<double> floor_z, double max_speed_mps, bool stairs);
  const Phase* find(double t_s) const;

  MotionLimits limits_;
  std::function<double(const Eigen::Vector2d&)> floor_z_;
  std::vector<Phase> phases_;
  Eigen::Vector2d position_ = Eigen::Vector2d::Zero();
  double yaw_ = 0.0, distance_ = 0.0, floor_here_ = 0.0;
  int storey_ = 0;
};

}  // namespace bimloc::sim
