// A scenario file (YAML, in scenarios/): world, storey, start, motion, duration, sensor,
// odometry, localizer settings, seed and expectations. See scenarios/README.md for the keys.
#pragma once

#include "sim/base/base_trajectory.hpp"
#include "sim/base/motion_config.hpp"
#include "sim/lidar/vlp16_config.hpp"
#include "sim/odometry/barometer.hpp"
#include "sim/odometry/odometry_config.hpp"
#include "sim/world/site_config.hpp"

#include <nlohmann/json.hpp>

#include <map>
#include <optional>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace bimloc::sim {

class World;

// Every problem with a scenario: "FILE:LINE: message" (LINE where the YAML node is known).
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StartConfig {
  enum class Kind { Room, Pose, RandomInRoom, OutsideRooms };
  Kind kind = Kind::Room;          // Room: the room's centre; RandomInRoom: a random free pose in it;
                                   // OutsideRooms: a random free spot in no room (sim/base/outside_rooms.hpp)
  std::string room;                // name, long name or GlobalId (Room, RandomInRoom)
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();  // x, y, yaw (rad) in the map frame (Pose)
  std::optional<double> yaw_rad;   // for Room: the heading (default 0); RandomInRoom: random if unset
  int line = 0;                    // where it was given, for messages
};

// Pass criteria, used by the runner (`bimloc run`).
struct Expectations {
  bool converge = true;
  double max_convergence_time_s = 60.0;
  double max_position_error_m = 0.5;
  double max_yaw_error_deg = 10.0;
  double max_ate_m = 0.2;
};

struct Scenario {
  std::string file;     // the YAML file, for messages
  std::string name;     // default: the file's stem
  std::string world;    // plan (.ifc), extract folder or mesh; resolved relative to the file
  std::string storey = "0";  // "auto": the localizer is not told (scenarioStorey finds the simulator's)
  StartConfig start;
  MotionConfig motion;
  double duration_s = 30.0;
  Vlp16Config sensor;
  OdometryConfig odometry;
  BarometerConfig barometer;  // `--altitude`: the localizer is given the base's altitude
  nlohmann::json localizer = nlohmann::json::object();  // settings for the localizer (next issues)
  std::uint64_t seed = 0;
  // How the simulated site differs from the plan (walls, glass, doors); the localizer still
  // gets only the plan. Drawn from `seed`.
  SiteConfig site;
  Expectations expect;
  // Line of each key as given, by dotted name ("storey", "motion.rooms.1", "motion.waypoints.0"),
  // for the messages of checks made later (checkScenarioAgainstWorld).
  std::map<std::string, int> lines;
};

// Parses and validates a scenario file. Unknown keys, wrong types and out-of-range values
// are ScenarioErrors naming the file and line.
Scenario loadScenario(const std::string& path);

// Checks the scenario against its world: the storey exists, the start and tour rooms exist
// (an unknown room is an error listing the rooms of that storey), waypoints are inside.
void checkScenarioAgainstWorld(const Scenario& scenario, const World& world);

// The scenario's storey in `world` (ScenarioError naming the file and line when it has none).
// With `storey: auto` the simulator still needs one: the storey of the start room, which must
// be a room of exactly one storey.
std::size_t scenarioStorey(const Scenario& scenario, const World& world);

// Whether the localizer is told the storey: false with `storey: auto` or `localizer: {storey: auto}`.
bool storeyGiven(const Scenario& scenario);

// The start as a map-frame pose on the scenario's storey: a room's centre (or, when the body
// does not fit there, the nearest spot where it does), the given pose, a random spot where
// the body fits in the room, or one in no room (outside_rooms), drawn from the seed (random
// heading unless yaw_deg is given).
Pose2 startPose(const Scenario& scenario, const World& world);

// The scenario's base trajectory: startPose, then BaseTrajectory::plan on its storey. A motion
// the body cannot make is a ScenarioError at the line to blame: the start, the waypoint that
// ends the segment hitting the building, or the motion.
BaseTrajectory planTrajectory(const Scenario& scenario, const World& world);

}  // namespace bimloc::sim
