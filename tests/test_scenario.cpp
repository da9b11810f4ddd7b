// Scenario files: every key read, defaults, and every kind of mistake reported with the file and
// the line; then the checks against the default world and the example scenarios.
#include "sim/scenario/localizer_config.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/world/world.hpp"
#include "test_support.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <gtest/gtest.h>

#include <chrono>

#include <filesystem>
#include <fstream>
#include <memory>

namespace bimloc::sim {
namespace {

namespace fs = std::filesystem;

const std::string kWorld = std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc";

std::string writeScenario(const std::string& text, const std::string& name = "scenario.yaml") {
  const std::string path = test::tempDir("scenario") + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// The head every test file shares: 2 lines, so the next key is on line 3.
std::string head() { return "world: " + kWorld + "\nstart: {room: R101}\n"; }

const World& siteOffice() {
  static const std::unique_ptr<World> world = std::make_unique<World>(World::fromPlan(kWorld));
  return *world;
}

// Loads `text` and expects a ScenarioError at `line` containing `part`.
void expectError(const std::string& text, int line, const std::string& part) {
  const std::string path = writeScenario(text);
  try {
    loadScenario(path);
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const ScenarioError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ":" + std::to_string(line) + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

// Loads `text` (valid) and expects checkScenarioAgainstWorld to fail at `line` with `part`.
void expectWorldError(const std::string& text, int line, const std::string& part) {
  const std::string path = writeScenario(text);
  const Scenario s = loadScenario(path);
  try {
    checkScenarioAgainstWorld(s, siteOffice());
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const ScenarioError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ":" + std::to_string(line) + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

TEST(Scenario, LoadsEveryKey) {
  const std::string dir = test::tempDir("scenario-full");
  fs::copy_file(kWorld, dir + "/office.ifc");
  const std::string path = dir + "/full.yaml";
  std::ofstream(path) << R"(# every key
name: full tour
world: office.ifc
storey: Ground floor
start: {room: R101, yaw_deg: 90}
motion:
  type: waypoints
  waypoints: [[2, 4], [2.75, 6.12, 180]]
  max_speed_mps: 0.6
  max_turn_rate_dps: 45
  max_accel_mps2: 0.4
  max_turn_accel_dps2: 90
  body_radius_m: 0.25
  gait: {step_frequency_hz: 1.8, bob_amplitude_m: 0.02, roll_amplitude_deg: 2, pitch_amplitude_deg: 1, body_height_m: 0.55}
duration_s: 45
sensor:
  rpm: 1200
  min_range_m: 0.5
  max_range_m: 80
  range_noise_sigma_m: 0.01
  dropout_probability: 0.05
  motion_distortion: false
  packets: no
  mount: {xyz: [0.1, 0, 0.3], rpy_deg: [0, 0, 90]}
odometry: {preset: lidar, rate_hz: 100, alpha1: 0.02, yaw_bias_sigma_rad_per_m: 0.001}
localizer:
  particles: 500
  method: pf
  planes: {min_inliers: 50}
  pf: {use_hypotheses: false}
  sgraph: {window_keyframes: 8}
seed: 42
expect: {converge: false, max_convergence_time_s: 20, max_position_error_m: 0.3, max_yaw_error_deg: 5, max_ate_m: 0.1}
)";
  const Scenario s = loadScenario(path);
  EXPECT_EQ(s.file, path);
  EXPECT_EQ(s.name, "full tour");
  EXPECT_EQ(s.world, dir + "/office.ifc");
  EXPECT_EQ(s.storey, "Ground floor");
  EXPECT_EQ(s.start.kind, StartConfig::Kind::Room);
  EXPECT_EQ(s.start.room, "R101");
  ASSERT_TRUE(s.start.yaw_rad.has_value());
  EXPECT_NEAR(*s.start.yaw_rad, M_PI / 2, 1e-12);
  EXPECT_EQ(s.start.line, 5);
  EXPECT_EQ(s.motion.kind, MotionConfig::Kind::Waypoints);
  ASSERT_EQ(s.motion.waypoints.size(), 2u);
  EXPECT_EQ(s.motion.waypoints[0].xy, Eigen::Vector2d(2, 4));
  EXPECT_FALSE(s.motion.waypoints[0].yaw_rad.has_value());
  EXPECT_NEAR(s.motion.waypoints[1].yaw_rad.value_or(0), M_PI, 1e-12);
  EXPECT_EQ(s.motion.max_speed_mps, 0.6);
  EXPECT_EQ(s.motion.max_turn_rate_dps, 45);
  EXPECT_EQ(s.motion.max_accel_mps2, 0.4);
  EXPECT_EQ(s.motion.max_turn_accel_dps2, 90);
  EXPECT_EQ(s.motion.body_radius_m, 0.25);
  EXPECT_EQ(s.motion.gait.step_frequency_hz, 1.8);
  EXPECT_EQ(s.motion.gait.bob_amplitude_m, 0.02);
  EXPECT_EQ(s.motion.gait.roll_amplitude_deg, 2);
  EXPECT_EQ(s.motion.gait.pitch_amplitude_deg, 1);
  EXPECT_EQ(s.motion.gait.body_height_m, 0.55);
  EXPECT_EQ(s.duration_s, 45);
  EXPECT_EQ(s.sensor.rpm, 1200);
  EXPECT_EQ(s.sensor.min_range_m, 0.5);
  EXPECT_EQ(s.sensor.max_range_m, 80);
  EXPECT_EQ(s.sensor.range_noise_sigma_m, 0.01);
  EXPECT_EQ(s.sensor.dropout_probability, 0.05);
  EXPECT_FALSE(s.sensor.motion_distortion);
  EXPECT_FALSE(s.sensor.use_packets);
  EXPECT_TRUE(s.sensor.T_base_lidar.translation().isApprox(Eigen::Vector3d(0.1, 0, 0.3)));
  EXPECT_TRUE((s.sensor.T_base_lidar.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  const OdometryConfig lidar = odometryPreset("lidar");
  EXPECT_EQ(s.odometry.preset, "custom");  // lidar with its own alpha1
  EXPECT_EQ(s.odometry.rate_hz, 100);
  EXPECT_EQ(s.odometry.alpha1, 0.02);
  EXPECT_EQ(s.odometry.alpha2, lidar.alpha2);
  EXPECT_EQ(s.odometry.scale_bias_walk_per_sqrt_m, lidar.scale_bias_walk_per_sqrt_m);
  EXPECT_EQ(s.odometry.scale_bias_sigma, lidar.scale_bias_sigma);
  EXPECT_EQ(s.odometry.yaw_bias_sigma_rad_per_m, 0.001);
  EXPECT_EQ(s.localizer, nlohmann::json::parse(R"({"particles": 500, "method": "pf", "planes": {"min_inliers": 50},
                                                   "pf": {"use_hypotheses": false}, "sgraph": {"window_keyframes": 8}})"));
  // ... and each of them reaches the localizer's config (no key the runner would reject).
  const LocalizerSettings settings = readLocalizerSettings(s.localizer, s.file, s.lines);
  EXPECT_EQ(settings.config.method, LocalizerMethod::Pf);
  EXPECT_EQ(settings.config.pf.particles, 500);
  EXPECT_EQ(settings.config.planes.min_inliers, 50);
  EXPECT_FALSE(settings.config.pf.use_hypotheses);
  EXPECT_EQ(settings.config.sgraph.window_keyframes, 8);
  EXPECT_EQ(s.seed, 42u);
  EXPECT_FALSE(s.expect.converge);
  EXPECT_EQ(s.expect.max_convergence_time_s, 20);
  EXPECT_EQ(s.expect.max_position_error_m, 0.3);
  EXPECT_EQ(s.expect.max_yaw_error_deg, 5);
  EXPECT_EQ(s.expect.max_ate_m, 0.1);
  EXPECT_EQ(s.lines.at("motion.waypoints.1"), 8);
  EXPECT_NO_THROW(checkScenarioAgainstWorld(s, siteOffice()));
}

TEST(Scenario, Defaults) {
  const std::string path = writeScenario(head(), "minimal.yaml");
  const Scenario s = loadScenario(path);
  const Scenario defaults;
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.world, kWorld);
  EXPECT_EQ(s.storey, "0");
  EXPECT_FALSE(s.start.yaw_rad.has_value());
  EXPECT_EQ(s.motion.kind, MotionConfig::Kind::Stand);
  EXPECT_EQ(s.motion.max_speed_mps, MotionConfig{}.max_speed_mps);
  EXPECT_EQ(s.motion.gait.body_height_m, GaitConfig{}.body_height_m);
  EXPECT_EQ(s.duration_s, defaults.duration_s);
  EXPECT_EQ(s.sensor.rpm, Vlp16Config{}.rpm);
  EXPECT_TRUE(s.sensor.T_base_lidar.isApprox(Vlp16Config{}.T_base_lidar));
  const OdometryConfig legged = odometryPreset("legged");
  EXPECT_EQ(s.odometry.preset, "legged");
  EXPECT_EQ(s.odometry.alpha1, legged.alpha1);
  EXPECT_EQ(s.odometry.rate_hz, legged.rate_hz);
  EXPECT_EQ(s.localizer, nlohmann::json::object());
  EXPECT_EQ(s.seed, 0u);
  EXPECT_EQ(s.expect.max_ate_m, Expectations{}.max_ate_m);
}

TEST(Scenario, ErrorsNameTheFileAndLine) {
  expectError(head() + "duraton: 5\n", 3, "unknown key 'duraton' (did you mean 'duration_s'?)");
  expectError(head() + "motion:\n  type: tour\n  rooms: [R105]\n  max_sped_mps: 1\n", 6,
              "unknown key 'max_sped_mps' in 'motion' (did you mean 'max_speed_mps'?)");
  expectError(head() + "sensor:\n  mount: {xyz: [0, 0, 1], rpy: [0, 0, 0]}\n", 4, "did you mean 'rpy_deg'?");
  expectError(head() + "colour: red\n", 3, "unknown key 'colour' (valid keys: name, world,");
  expectError(head() + "seed: 1\nseed: 2\n", 4, "given twice (first at line 3)");
  // Wrong types.
  expectError(head() + "duration_s: long\n", 3, "duration_s must be a number, got 'long'");
  expectError(head() + "duration_s: '30'\n", 3, "duration_s must be a number");
  expectError(head() + "sensor: {motion_distortion: maybe}\n", 3, "sensor.motion_distortion must be true or false");
  expectError(head() + "motion: walk\n", 3, "motion must be a mapping");
  expectError(head() + "motion:\n  type: waypoints\n  waypoints: 5\n", 5, "must be a list of [x, y] or [x, y, yaw_deg]");
  expectError(head() + "motion:\n  type: waypoints\n  waypoints:\n    - [1, 2]\n    - [1, 2, 3, 4]\n", 7,
              "motion.waypoints[1] must be a list of 2 or 3 numbers, got 4 item(s)");
  expectError(head() + "motion: {type: tour, rooms: R105}\n", 3, "motion.rooms must be a list of room names");
  expectError(head() + "seed: -1\n", 3, "seed must be an integer");
  expectError(head() + "localizer: [1, 2]\n", 3, "localizer must be a mapping");
  // Out of range.
  expectError(head() + "duration_s: 0\n", 3, "duration_s must be in (0, 3600], got 0");
  expectError(head() + "duration_s: 4000\n", 3, "duration_s must be in (0, 3600]");
  expectError(head() + "sensor:\n  rpm: 1300\n", 4, "sensor.rpm must be in [300, 1200], got 1300");
  expectError(head() + "sensor:\n  rpm: 610\n", 4, "sensor.rpm must be a multiple of 60");
  expectError(head() + "sensor: {dropout_probability: 1.5}\n", 3, "must be in [0, 1]");
  expectError(head() + "sensor: {min_range_m: 5, max_range_m: 2}\n", 3, "min_range_m must be below");
  expectError(head() + "motion: {max_speed_mps: -0.5}\n", 3, "motion.max_speed_mps must be in (0, 3]");
  expectError(head() + "motion:\n  gait:\n    body_height_m: 0.2\n", 5, "body_radius_m must be below motion.gait.body_height_m");
  // Choices.
  expectError(head() + "motion:\n  type: tuor\n", 4, "must be one of stand, waypoints, tour, random_walk, disambiguate, got 'tuor' (did you mean 'tour'?)");
  expectError(head() + "odometry: {preset: wheeled}\n", 3, "odometry.preset must be one of legged, lidar, perfect, custom");
  expectError(head() + "motion:\n  type: tour\n  rooms: [R105]\n  waypoints: [[1, 2]]\n", 6,
              "'motion.waypoints' is only used with type: waypoints");
  expectError(head() + "motion: {type: tour}\n", 3, "missing required key 'motion.rooms'");
  // Start.
  expectError("world: " + kWorld + "\nstart: {}\n", 2, "start needs one of room, pose, random_in_room");
  expectError("world: " + kWorld + "\nstart:\n  room: R101\n  pose: [1, 2, 0]\n", 4, "start takes one of room, pose, random_in_room");
  expectError("world: " + kWorld + "\nstart: {pose: [1, 2, 0], yaw_deg: 3}\n", 2, "start.yaw_deg is part of start.pose");
  // Required keys and the world.
  expectError("# no world\nstart: {room: R101}\nduration_s: 10\n", 2, "missing required key 'world'");
  expectError("world: " + kWorld + "\n", 1, "missing required key 'start'");
  expectError("world: nowhere/office.ifc\nstart: {room: R101}\n", 1, "world 'nowhere/office.ifc' not found");
  // YAML syntax.
  expectError(head() + "motion: {type: tour\n", 4, "YAML syntax error");
  expectError(head() + "sensor:\n  rpm: 600\n rpm: 300\n", 5, "YAML syntax error");
}

TEST(Scenario, AliasCyclesAndAliasBombsAreRefusedWithTheirLine) {
  // An alias inside its own anchor recursed without end; nine levels of nine aliases ran for a
  // minute and took 22 GB. Both are refused at once, naming the line.
  const auto started = std::chrono::steady_clock::now();
  expectError(head() + "localizer: &x {a: *x}\n", 3, "nested more than 32 levels deep");
  std::string bomb = head() + "localizer:\n  l0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, 1]\n";
  for (int level = 1; level < 9; ++level) {
    bomb += "  l" + std::to_string(level) + ": &a" + std::to_string(level) + " [";
    for (int k = 0; k < 9; ++k) bomb += (k ? ", *a" : "*a") + std::to_string(level - 1);
    bomb += "]\n";
  }
  expectError(bomb, 4, "expands to more than 100000 values");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 10.0);
}

// Found by the fuzz test: a name that is not UTF-8 passed the loader and failed only when
// metadata.json was written, in nlohmann's words and without the file; 1e999 or .nan in the
// free-form localizer: section passed on as a string.
TEST(Scenario, BytesThatAreNotUtf8AndNonFiniteNumbersAreRefusedWithTheirLine) {
  expectError(head() + "name: caf\xE9\n", 3, "not UTF-8 text: byte 0xE9 in column 10");
  expectError(head() + "name: \xC0\x80\n", 3, "not UTF-8 text: byte 0xC0");  // an overlong NUL
  expectError(head() + "localizer: {particles: 1e999}\n", 3, "'1e999' is not a finite number");
  expectError(head() + "localizer:\n  prior_sigma_m: .nan\n", 4, "'.nan' is not a finite number");
  EXPECT_NO_THROW(loadScenario(writeScenario(head() + "name: caf\xC3\xA9 \xE2\x82\xAC\n")));  // UTF-8 itself is fine
}

TEST(Scenario, EmptyAndMissingFiles) {
  EXPECT_THROW(loadScenario(writeScenario("")), ScenarioError);
  EXPECT_THROW(loadScenario(writeScenario("# only a comment\n")), ScenarioError);
  EXPECT_THROW(loadScenario(test::tempDir("scenario") + "/absent.yaml"), ScenarioError);
  EXPECT_THROW(loadScenario(writeScenario("- a list\n- not a mapping\n")), ScenarioError);
}

TEST(Scenario, ChecksAgainstTheWorld) {
  // An unknown room lists the rooms of the storey, with their long names.
  expectWorldError(head() + "motion:\n  type: tour\n  rooms:\n    - C100\n    - R109\n", 7,
                   "unknown room 'R109' on storey 'Ground floor'; its rooms: R101 (Office),");
  expectWorldError("world: " + kWorld + "\nstart:\n  room: Kitchen\n", 3, "C100 (Corridor)");
  expectWorldError(head() + "motion: {type: random_walk, room: Lab}\n", 3, "unknown room 'Lab'");
  // A long name is fine when one room has it, ambiguous when eight do.
  EXPECT_NO_THROW(checkScenarioAgainstWorld(loadScenario(writeScenario("world: " + kWorld + "\nstart: {room: Corridor}\n")),
                                            siteOffice()));
  expectWorldError("world: " + kWorld + "\nstart: {room: Office}\n", 2, "room 'Office' is ambiguous");
  expectWorldError(head() + "storey: Roof\n", 3, "no storey 'Roof' (storeys: 0 'Ground floor')");
  expectWorldError(head() + "motion:\n  type: waypoints\n  waypoints: [[2, 4], [30, 4]]\n", 5,
                   "motion.waypoints[1] (30.00, 4.00) is outside the building");
  expectWorldError("world: " + kWorld + "\nstart: {pose: [-5, 2, 0]}\n", 2, "start.pose (-5.00, 2.00) is outside");
  expectWorldError("world: " + kWorld + "\nstart: {pose: [4.06, 2.5, 0]}\nmotion: {type: random_walk}\n", 3,
                   "is in no room");
}

TEST(Scenario, PlanningErrorsNameTheLine) {
  // From R101 east through the divider to R102: the second waypoint's segment hits the wall.
  const std::string path = writeScenario(head() + "motion:\n  type: waypoints\n  waypoints:\n    - [2, 4]\n    - [6, 4]\n");
  try {
    planTrajectory(loadScenario(path), siteOffice());
    ADD_FAILURE() << "a path through a wall was planned";
  } catch (const ScenarioError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ":7: motion segment 2 from (2.00, 4.00) to (6.00, 4.00) hits the building at (", 0), 0u)
        << message;
  }
  const std::string wall = writeScenario("world: " + kWorld + "\nstart: {pose: [4.06, 2.5, 0]}\n");
  try {
    planTrajectory(loadScenario(wall), siteOffice());
    ADD_FAILURE() << "a start inside a wall was planned";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(wall + ":2: the start (4.06, 2.50) leaves no room", 0), 0u) << e.what();
  }
}

TEST(Scenario, StartPose) {
  const auto load = [](const std::string& start, const std::string& more = "") {
    return loadScenario(writeScenario("world: " + kWorld + "\nstart: " + start + "\n" + more));
  };
  const Pose2 centre = startPose(load("{room: R101, yaw_deg: 90}"), siteOffice());
  EXPECT_NEAR(centre.x, 2.0, 1e-9);
  EXPECT_NEAR(centre.y, 2.5, 1e-9);
  EXPECT_NEAR(centre.yaw, M_PI / 2, 1e-12);
  const Pose2 pose = startPose(load("{pose: [8, 6, -90]}"), siteOffice());
  EXPECT_EQ(pose.x, 8.0);
  EXPECT_NEAR(pose.yaw, -M_PI / 2, 1e-12);
  const Pose2 a = startPose(load("{random_in_room: R107}", "seed: 9\n"), siteOffice());
  const Pose2 b = startPose(load("{random_in_room: R107}", "seed: 9\n"), siteOffice());
  const Pose2 c = startPose(load("{random_in_room: R107}", "seed: 10\n"), siteOffice());
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.yaw, b.yaw);
  EXPECT_NE(a.x, c.x);
  const auto& rooms = siteOffice().building().storeys.at(0).rooms;
  const auto r107 = std::find_if(rooms.begin(), rooms.end(), [](const bim::Room& r) { return r.name == "R107"; });
  ASSERT_NE(r107, rooms.end());
  EXPECT_TRUE(bim::pointInPolygon(r107->footprint, {a.x, a.y}));
}

TEST(Scenario, ExampleScenariosLoadCheckAndPlan) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(BIMLOC_SCENARIOS_DIR)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    ++count;
    const Scenario s = loadScenario(entry.path().string());
    const World world = World::load(s.world);
    ASSERT_NO_THROW(checkScenarioAgainstWorld(s, world));
    const auto trajectory = planTrajectory(s, world);
    EXPECT_LE(trajectory.script_duration_s(), s.motion.kind == MotionConfig::Kind::RandomWalk
                                                  ? s.duration_s + 60.0
                                                  : s.duration_s);  // the tours fit their duration
  }
  EXPECT_GE(count, 3);
}

}  // namespace
}  // namespace bimloc::sim
