// How the simulated legged base moves: the script and the limits of a Spot-like body.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim {

struct Waypoint {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  // map frame, metres
  std::optional<double> yaw_rad;                 // turn in place to this heading on arrival
};

struct GaitConfig {
  double step_frequency_hz = 2.0;  // Spot's trot is about 2 steps per second
  double bob_amplitude_m = 0.01;   // body height oscillation at the step frequency
  double roll_amplitude_deg = 1.0;
  double pitch_amplitude_deg = 0.5;
  double body_height_m = 0.5;      // base_link above the floor (Spot standing)
};

struct MotionConfig {
  enum class Kind { Stand, Waypoints, Tour, RandomWalk };
  Kind kind = Kind::Stand;
  std::vector<Waypoint> waypoints;  // Kind::Waypoints
  std::vector<std::string> rooms;   // Kind::Tour: room names or ids, visited in order through the doors
  // Kind::Tour: the storey (name, GlobalId or index) of each room, as many as rooms; empty: all
  // on the start storey. A room on another storey is reached over the stairs (issue 31).
  std::vector<std::string> storeys;
  // Kind::Tour (`--multi-storey`): after the listed rooms, the base explores every storey the
  // stairs lead to from its start, in turn (the nearest by stairs first), an equal share of the
  // duration on each, and goes on exploring the last one.
  bool all_storeys = false;
  std::string walk_room;            // Kind::RandomWalk: the room to wander in (default: the start room)
  // Kind::Tour: rooms out of reach (another flat, closed doors) are left out instead of an
  // error; reaching none, the base explores (explore_after_tour) or else wanders in its start
  // room. Generated tours set it.
  bool skip_unreachable_rooms = false;
  // Kind::Tour: the listed rooms visited before the duration is up, the base goes on exploring
  // (the nearest room not yet visited that it can reach, and so on; with none left, the next
  // round of its rooms, and only when it can reach none, it wanders where it is) instead of
  // standing: a robot localizing keeps moving. Generated tours set it.
  bool explore_after_tour = false;
  // The base walks where the localizer suggests looking (LocalizationResult::goal) while it
  // searches, and follows the script (a tour) when there is no goal and after convergence
  // (sim/runner/guided_walk.hpp). Scenario `type: disambiguate`, `--motion disambiguate`.
  bool disambiguate = false;
  double max_speed_mps = 0.8;
  double max_turn_rate_dps = 60.0;
  double max_accel_mps2 = 0.5;
  double max_turn_accel_dps2 = 120.0;  // turns ramp up and down too: full turn rate in 0.5 s
  double body_radius_m = 0.3;       // Spot is about 1.1 x 0.5 m: a 0.3 m circle clears door frames
  GaitConfig gait;
};

}  // namespace bimloc::sim
