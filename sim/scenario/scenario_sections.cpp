#include "sim/scenario/scenario_sections.hpp"
#include "sim/common/angles.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace bimloc::sim::detail {
namespace {

// Map coordinates: a building is never kilometres wide; this only catches unit slips (mm).
const Range kCoordinate = Range::closed(-1e4, 1e4);
const Range kAngleDeg = Range::closed(-360.0, 360.0);

Mapping readGait(const Mapping& motion, GaitConfig& gait) {
  const Mapping g = motion.mapping(
      "gait", {"step_frequency_hz", "bob_amplitude_m", "roll_amplitude_deg", "pitch_amplitude_deg", "body_height_m"});
  g.read("step_frequency_hz", gait.step_frequency_hz, Range::positive(5.0));
  g.read("bob_amplitude_m", gait.bob_amplitude_m, Range::closed(0.0, 0.1));
  g.read("roll_amplitude_deg", gait.roll_amplitude_deg, Range::closed(0.0, 10.0));
  g.read("pitch_amplitude_deg", gait.pitch_amplitude_deg, Range::closed(0.0, 10.0));
  g.read("body_height_m", gait.body_height_m, Range::closed(0.1, 2.0));
  return g;
}

void readWaypoints(const Mapping& m, MotionConfig& motion, std::map<std::string, int>& lines) {
  m.require("waypoints");
  const YAML::Node& list = m.value("waypoints");
  if (!list.IsSequence() || list.size() == 0)
    m.fail("waypoints", "motion.waypoints must be a list of [x, y] or [x, y, yaw_deg], got " + describe(list));
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string what = "motion.waypoints[" + std::to_string(i) + "]";
    const std::vector<double> v = m.numbers(list[i], what, m.line("waypoints"), 2, 3, kCoordinate);
    if (v.size() == 3 && !kAngleDeg.contains(v[2]))
      fail(m.file(), lineOf(list[i]), what + " yaw_deg must be in " + kAngleDeg.str());
    Waypoint w;
    w.xy = {v[0], v[1]};
    if (v.size() == 3) w.yaw_rad = v[2] * kDegToRad;
    motion.waypoints.push_back(w);
    lines["motion.waypoints." + std::to_string(i)] = lineOf(list[i]) > 0 ? lineOf(list[i]) : m.line("waypoints");
  }
}

void readRooms(const Mapping& m, MotionConfig& motion, std::map<std::string, int>& lines) {
  m.require("rooms");
  const YAML::Node& list = m.value("rooms");
  if (!list.IsSequence() || list.size() == 0)
    m.fail("rooms", "motion.rooms must be a list of room names, e.g. [C100, R105], got " + describe(list));
  for (std::size_t i = 0; i < list.size(); ++i) {
    const int line = lineOf(list[i]) > 0 ? lineOf(list[i]) : m.line("rooms");
    if (!list[i].IsScalar() || list[i].Scalar().empty())
      fail(m.file(), line, "motion.rooms[" + std::to_string(i) + "] must be a room name, got " + describe(list[i]));
    motion.rooms.push_back(list[i].Scalar());
    lines["motion.rooms." + std::to_string(i)] = line;
  }
}

// The storey of each room (issue 31): one name for all of them, or one per room.
void readTourStoreys(const Mapping& m, MotionConfig& motion, std::map<std::string, int>& lines) {
  if (!m.has("storeys")) return;
  const YAML::Node& list = m.value("storeys");
  if (!list.IsSequence() || (list.size() != 1 && list.size() != motion.rooms.size()))
    m.fail("storeys", "motion.storeys must be a list of storey names or indices, one for every room (" +
                          std::to_string(motion.rooms.size()) + ") or one for all, got " + describe(list));
  for (std::size_t i = 0; i < list.size(); ++i) {
    const int line = lineOf(list[i]) > 0 ? lineOf(list[i]) : m.line("storeys");
    if (!list[i].IsScalar() || list[i].Scalar().empty())
      fail(m.file(), line, "motion.storeys[" + std::to_string(i) + "] must be a storey name or index, got " + describe(list[i]));
    motion.storeys.push_back(list[i].Scalar());
    lines["motion.storeys." + std::to_string(i)] = line;
  }
  if (motion.storeys.size() == 1) motion.storeys.assign(motion.rooms.size(), motion.storeys.front());
}

}  // namespace

StartConfig readStart(const Mapping& top, std::map<std::string, int>& lines) {
  top.require("start");
  const Mapping m = top.mapping("start", {"room", "pose", "random_in_room", "outside_rooms", "yaw_deg"});
  StartConfig start;
  start.line = top.line("start");
  lines["start"] = start.line;
  std::vector<std::string> kinds;
  for (const char* k : {"room", "pose", "random_in_room", "outside_rooms"})
    if (m.has(k)) kinds.push_back(k);
  const std::string one_of = "one of room, pose, random_in_room, outside_rooms";
  if (kinds.empty()) fail(m.file(), start.line, "start needs " + one_of);
  if (kinds.size() > 1) m.fail(kinds[1], "start takes " + one_of + ", got " + kinds[0] + " and " + kinds[1]);
  if (m.has("outside_rooms")) {
    bool outside = false;
    m.read("outside_rooms", outside);
    if (!outside) m.fail("outside_rooms", "start.outside_rooms: only 'true' (a random spot in no room) is meaningful");
    start.kind = StartConfig::Kind::OutsideRooms;
    start.line = m.line("outside_rooms");
    if (m.has("yaw_deg")) {
      double yaw_deg = 0.0;
      m.read("yaw_deg", yaw_deg, kAngleDeg);
      start.yaw_rad = yaw_deg * kDegToRad;
    }
    return start;
  }
  if (m.has("pose")) {
    if (m.has("yaw_deg")) m.fail("yaw_deg", "start.yaw_deg is part of start.pose ([x, y, yaw_deg])");
    const std::vector<double> v = m.numbers(m.value("pose"), "start.pose", m.line("pose"), 2, 3, kCoordinate);
    if (v.size() == 3 && !kAngleDeg.contains(v[2])) m.fail("pose", "start.pose yaw_deg must be in " + kAngleDeg.str());
    start.kind = StartConfig::Kind::Pose;
    start.pose = {v[0], v[1], v.size() == 3 ? v[2] * kDegToRad : 0.0};
    start.line = m.line("pose");
    return start;
  }
  start.kind = m.has("room") ? StartConfig::Kind::Room : StartConfig::Kind::RandomInRoom;
  const std::string key = m.has("room") ? "room" : "random_in_room";
  m.read(key, start.room);
  start.line = m.line(key);
  if (m.has("yaw_deg")) {
    double yaw_deg = 0.0;
    m.read("yaw_deg", yaw_deg, kAngleDeg);
    start.yaw_rad = yaw_deg * kDegToRad;
  }
  return start;
}

MotionConfig readMotion(const Mapping& top, std::map<std::string, int>& lines) {
  const Mapping m = top.mapping("motion", {"type", "waypoints", "rooms", "storeys", "room", "max_speed_mps", "max_turn_rate_dps",
                                           "max_accel_mps2", "max_turn_accel_dps2", "body_radius_m", "gait"});
  MotionConfig motion;
  std::string type = "stand";
  m.readChoice("type", type, {"stand", "waypoints", "tour", "random_walk", "disambiguate"});
  lines["motion"] = m.line();
  if (type != "waypoints") m.onlyWith("waypoints", "type: waypoints");
  if (type != "tour" && type != "disambiguate") m.onlyWith("rooms", "type: tour or disambiguate");
  if (type != "random_walk") m.onlyWith("room", "type: random_walk");
  if (type == "waypoints") motion.kind = MotionConfig::Kind::Waypoints, readWaypoints(m, motion, lines);
  if (type != "tour") m.onlyWith("storeys", "type: tour");
  if (type == "tour") motion.kind = MotionConfig::Kind::Tour, readRooms(m, motion, lines), readTourStoreys(m, motion, lines);
  // Walk where the localizer says to look; without a goal, and once converged, a tour of the
  // rooms listed (if any) and on through every room it can reach.
  if (type == "disambiguate") {
    motion.kind = MotionConfig::Kind::Tour, motion.disambiguate = true;
    motion.skip_unreachable_rooms = motion.explore_after_tour = true;
    if (m.has("rooms")) readRooms(m, motion, lines);
  }
  if (type == "random_walk") {
    motion.kind = MotionConfig::Kind::RandomWalk;
    m.read("room", motion.walk_room);
    lines["motion.room"] = m.line("room");
  }
  // Spot: 1.6 m/s top speed; the ranges only catch slips of unit or sign.
  m.read("max_speed_mps", motion.max_speed_mps, Range::positive(3.0));
  m.read("max_turn_rate_dps", motion.max_turn_rate_dps, Range::positive(360.0));
  m.read("max_accel_mps2", motion.max_accel_mps2, Range::positive(10.0));
  m.read("max_turn_accel_dps2", motion.max_turn_accel_dps2, Range::positive(1440.0));
  m.read("body_radius_m", motion.body_radius_m, Range::closed(0.05, 1.5));
  const Mapping gait = readGait(m, motion.gait);
  if (motion.body_radius_m >= motion.gait.body_height_m) {
    const std::string message =
        "motion.body_radius_m must be below motion.gait.body_height_m (the body sphere, centred at body height, "
        "would touch the floor)";
    if (gait.has("body_height_m")) gait.fail("body_height_m", message);
    m.fail("body_radius_m", message);
  }
  return motion;
}

Vlp16Config readSensor(const Mapping& top) {
  const Mapping m = top.mapping("sensor", {"rpm", "min_range_m", "max_range_m", "range_noise_sigma_m",
                                           "dropout_probability", "motion_distortion", "deskew", "packets", "mount"});
  Vlp16Config sensor;
  m.read("rpm", sensor.rpm, Range::closed(300.0, 1200.0));
  if (std::fmod(sensor.rpm, 60.0) != 0.0)
    m.fail("rpm", "sensor.rpm must be a multiple of 60 (300, 360, ..., 1200), got " + m.value("rpm").Scalar());
  m.read("min_range_m", sensor.min_range_m, Range::positive(10.0));
  m.read("max_range_m", sensor.max_range_m, Range::positive(200.0));
  if (sensor.min_range_m >= sensor.max_range_m)
    m.fail(m.has("max_range_m") ? "max_range_m" : "min_range_m", "sensor.min_range_m must be below sensor.max_range_m");
  m.read("range_noise_sigma_m", sensor.range_noise_sigma_m, Range::closed(0.0, 1.0));
  m.read("dropout_probability", sensor.dropout_probability, Range::closed(0.0, 1.0));
  m.read("motion_distortion", sensor.motion_distortion);
  m.read("deskew", sensor.deskew);
  m.read("packets", sensor.use_packets);

  const Mapping mount = m.mapping("mount", {"xyz", "rpy_deg"});
  Eigen::Vector3d xyz = sensor.T_base_lidar.translation();
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  if (mount.has("xyz"))
    xyz = Eigen::Vector3d(mount.numbers(mount.value("xyz"), "sensor.mount.xyz", mount.line("xyz"), 3, 3,
                                        Range::closed(-10.0, 10.0)).data());
  if (mount.has("rpy_deg"))
    rpy = Eigen::Vector3d(mount.numbers(mount.value("rpy_deg"), "sensor.mount.rpy_deg", mount.line("rpy_deg"), 3, 3,
                                        kAngleDeg).data()) * kDegToRad;
  if (mount.has("xyz") || mount.has("rpy_deg")) {
    // ROS's convention (URDF, tf): fixed-axis roll, then pitch, then yaw.
    sensor.T_base_lidar = Eigen::Translation3d(xyz) * Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX());
  }
  return sensor;
}

OdometryConfig readOdometry(const Mapping& top) {
  const Mapping m = top.mapping("odometry", {"preset", "rate_hz", "alpha1", "alpha2", "alpha3", "alpha4", "scale_bias_sigma",
                                             "scale_bias_walk_per_sqrt_m", "yaw_bias_sigma_rad_per_m",
                                             "yaw_bias_walk_rad_per_m_per_sqrt_m", "stair_height_scale_sigma",
                                             "stair_slip_factor"});
  std::string preset = "legged";
  m.readChoice("preset", preset, {"legged", "lidar", "perfect", "custom"});
  OdometryConfig odometry;
  try {
    // custom: no noise but what the file gives.
    odometry = odometryPreset(preset == "custom" ? "perfect" : preset);
  } catch (const std::invalid_argument& e) {
    m.fail("preset", e.what());
  }
  m.read("rate_hz", odometry.rate_hz, Range::positive(1000.0));
  bool noise_given = false;
  const auto noise = [&](const char* key, double& value, const Range& range) {
    m.read(key, value, range);
    noise_given = noise_given || m.has(key);
  };
  noise("alpha1", odometry.alpha1, Range::closed(0.0, 10.0));
  noise("alpha2", odometry.alpha2, Range::closed(0.0, 10.0));
  noise("alpha3", odometry.alpha3, Range::closed(0.0, 10.0));
  noise("alpha4", odometry.alpha4, Range::closed(0.0, 10.0));
  noise("scale_bias_sigma", odometry.scale_bias_sigma, Range::closed(0.0, 1.0));
  noise("scale_bias_walk_per_sqrt_m", odometry.scale_bias_walk_per_sqrt_m, Range::closed(0.0, 1.0));
  noise("yaw_bias_sigma_rad_per_m", odometry.yaw_bias_sigma_rad_per_m, Range::closed(0.0, 1.0));
  noise("yaw_bias_walk_rad_per_m_per_sqrt_m", odometry.yaw_bias_walk_rad_per_m_per_sqrt_m, Range::closed(0.0, 1.0));
  noise("stair_height_scale_sigma", odometry.stair_height_scale_sigma, Range::closed(0.0, 1.0));
  noise("stair_slip_factor", odometry.stair_slip_factor, Range::closed(1.0, 100.0));
  // A preset with other noise is no longer that preset: reports must not call it one.
  odometry.preset = noise_given ? "custom" : preset;
  return odometry;
}

Expectations readExpect(const Mapping& top) {
  const Mapping m = top.mapping("expect", {"converge", "max_convergence_time_s", "max_position_error_m",
                                           "max_yaw_error_deg", "max_ate_m"});
  Expectations expect;
  m.read("converge", expect.converge);
  m.read("max_convergence_time_s", expect.max_convergence_time_s, Range::positive(3600.0));
  m.read("max_position_error_m", expect.max_position_error_m, Range::positive(100.0));
  m.read("max_yaw_error_deg", expect.max_yaw_error_deg, Range::positive(180.0));
  m.read("max_ate_m", expect.max_ate_m, Range::positive(100.0));
  return expect;
}

}  // namespace bimloc::sim::detail
